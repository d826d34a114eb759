//! Distance maps (`sdfc_compiler::bake`): the baked field against exact distances, its proven
//! Lipschitz constant against measured slopes, and the ball test on random scenes.

use glam::DVec3;
use sdfc_compiler::bake::Volume;
use sdfc_compiler::reference::eval;
use sdfc_tests::Rng;

/// A field to bake.
type Field<'a> = &'a (dyn Fn(DVec3) -> f64 + Sync);

/// Exact distances to a sphere and to a box, baked at 16 to 128 points: outside the shape and
/// within two cells of its surface (where rays approach it) the baked field is within a tenth of
/// a cell of the exact one for the sphere and 0.4 of a cell for the box (trilinear
/// interpolation across a cell holding an edge or corner reads the kinked field inside), and
/// the error shrinks with the cell. (Inside, where the exact field
/// has kinks — the sphere's centre, the box's medial planes, which reach its edges — trilinear
/// interpolation rounds them off by up to half a cell or more: printed, not asserted.)
#[test]
fn a_baked_sphere_and_box_are_their_distances_to_a_fraction_of_a_cell() {
    let sphere = |p: DVec3| p.length() - 0.7;
    let cube = |p: DVec3| {
        let q = p.abs() - DVec3::new(0.6, 0.3, 0.45);
        q.max(DVec3::ZERO).length() + q.max_element().min(0.0)
    };
    let shapes: [(&str, Field, DVec3, f64); 2] = [
        ("sphere", &sphere, DVec3::splat(0.7), 0.1),
        ("box", &cube, DVec3::new(0.6, 0.3, 0.45), 0.4),
    ];
    let mut r = Rng::new(34);
    for (name, field, half, cells) in shapes {
        let mut last = f64::INFINITY;
        for res in [16, 32, 64, 128] {
            let v = Volume::bake(field, -half, half, res);
            let g = v.grid;
            let (mut near, mut anywhere): (f64, f64) = (0.0, 0.0);
            for _ in 0..40_000 {
                let p = g.lo + (g.hi - g.lo) * DVec3::new(r.unit(), r.unit(), r.unit());
                let e = (v.field(p) - field(p)).abs();
                anywhere = anywhere.max(e);
                if (0.0..2.0 * g.h).contains(&field(p)) {
                    near = near.max(e);
                }
            }
            println!(
                "{name} at {res}: cell {:.4}, worst error outside within 2 cells {:.2e} ({:.3} cells), anywhere {:.3} cells, λ {:.4}",
                g.h,
                near,
                near / g.h,
                anywhere / g.h,
                v.lambda
            );
            assert!(near < cells * g.h, "{name} at {res}: {near} (cell {})", g.h);
            assert!(near < last, "{name}: the error does not shrink at {res}");
            last = near;
        }
    }
}

/// The constant `lambda_of` claims bounds the interpolant's slope everywhere: central
/// differences at random points and around grid points never exceed it.
fn assert_slope_within(v: &Volume, r: &mut Rng, what: &str) -> f64 {
    let g = v.grid;
    let h = g.h * 1e-4;
    let mut steepest: f64 = 0.0;
    for _ in 0..4000 {
        let p = g.lo + (g.hi - g.lo) * DVec3::new(r.unit(), r.unit(), r.unit());
        let grad = DVec3::new(
            v.field(p + DVec3::X * h) - v.field(p - DVec3::X * h),
            v.field(p + DVec3::Y * h) - v.field(p - DVec3::Y * h),
            v.field(p + DVec3::Z * h) - v.field(p - DVec3::Z * h),
        ) / (2.0 * h);
        steepest = steepest.max(grad.length());
    }
    // (f32 values: the differences carry their rounding.)
    assert!(
        steepest <= v.lambda * (1.0 + 1e-3) + 1e-3,
        "{what}: slope {steepest} above the claimed λ {}",
        v.lambda
    );
    steepest
}

/// Random scenes of the fuzzers' generator baked at random resolutions: the slope never exceeds
/// the claimed λ, and the ball test holds — no point of the ball of radius |F(p)|/λ about p has
/// the other sign (so steps of F/λ never cross the baked surface). Baked with the field's
/// bound (evaluated only near the surface), the volume is the same to the bit.
#[test]
fn baked_random_scenes_keep_their_lambda_and_the_ball_test() {
    let cases = sdfc_tests::fuzz_cases(24);
    let seed = sdfc_tests::fuzz_seed(3400);
    let mut r = Rng::new(seed);
    let (mut baked, mut ratio): (usize, f64) = (0, 0.0);
    for i in 0..u64::from(cases) {
        let source = sdfc_tests::scenes::scene(seed + i);
        let Some(scene) = sdfc_compiler::check::compile(&source).scene else {
            continue;
        };
        // (The generator's doubling unions cost thousands of evaluations per point.)
        if scene.root_node().evaluations > 256.0 {
            continue;
        }
        // The mandelbulb's λ is its distance estimate's, not a proven bound (docs/lipschitz.md):
        // no claim about it here (CI seed 455712268 found one whose pruned bake differs).
        if source.contains("mandelbulb(") {
            continue;
        }
        let res = 8 + r.below(32);
        let field = |p: DVec3| eval::distance(&scene, p);
        let v = Volume::bake(&field, DVec3::splat(-2.0), DVec3::splat(2.0), res);
        let what = format!("seed {} at {res}\n{source}", seed + i);
        let pruned =
            Volume::bake_lipschitz(&field, 1.0, DVec3::splat(-2.0), DVec3::splat(2.0), res);
        assert!(
            pruned == v,
            "{what}: baked near the surface only, another volume"
        );
        let steepest = assert_slope_within(&v, &mut r, &what);
        if steepest > 0.5 {
            ratio = ratio.max(v.lambda / steepest);
        }
        let g = v.grid;
        for _ in 0..2000 {
            let p = g.lo + (g.hi - g.lo) * DVec3::new(r.unit(), r.unit(), r.unit());
            let f = v.field(p);
            let radius = f.abs() / v.lambda;
            let dir = DVec3::new(r.range(-1.0, 1.0), r.range(-1.0, 1.0), r.range(-1.0, 1.0));
            let q = p + dir.normalize_or_zero() * radius * r.unit() * 0.999;
            let fq = v.field(q);
            assert!(
                fq * f.signum() >= -1e-5 * g.h,
                "{what}: F({p}) = {f} but F({q}) = {fq} inside its ball"
            );
        }
        baked += 1;
    }
    println!("{baked} scenes baked; λ claimed up to {ratio:.2}× the steepest slope sampled");
    assert!(baked * 3 >= cases as usize, "only {baked} of {cases}");
}

/// The baked volumes of every reachable `bake` of a scene.
fn volumes_of(source: &str) -> Vec<std::sync::Arc<Volume>> {
    let checked = sdfc_compiler::check::compile(source);
    let scene = checked
        .scene
        .unwrap_or_else(|| panic!("{source}: {:?}", checked.diagnostics));
    scene.volumes()
}

/// A baked part is reused while its shape and resolution do not change: checking the scene
/// again, or with another part edited, gives the same volume (not baked again); another `res`
/// or another shape bakes anew.
#[test]
fn a_volume_is_reused_until_its_shape_or_resolution_changes() {
    let part = "bake(res = 24) { torus(0.6, 0.21) |> rotate(x, 37deg) }";
    let first = volumes_of(&format!("{part}\nsphere(0.3) at (3, 0, 0)"));
    let again = volumes_of(&format!("{part}\nsphere(0.3) at (3, 0, 0)"));
    let edited = volumes_of(&format!("{part}\nbox(0.5) at (-3, 1, 0)"));
    assert!(
        std::sync::Arc::ptr_eq(&first[0], &again[0]),
        "checked again: baked again"
    );
    assert!(
        std::sync::Arc::ptr_eq(&first[0], &edited[0]),
        "another part edited: baked again"
    );
    let finer = volumes_of(&part.replace("res = 24", "res = 25"));
    let other = volumes_of(&part.replace("0.21", "0.22"));
    for (what, v) in [("another res", &finer[0]), ("another shape", &other[0])] {
        assert!(!std::sync::Arc::ptr_eq(&first[0], v), "{what}: reused");
    }
    assert_ne!(first[0].grid.n, finer[0].grid.n);
}

/// A shape with no Lipschitz bound (a ramp whose height jumps where `atan2` crosses its cut)
/// is refused as it is and baked inside `bake`; more than two cells from the surface (by the
/// field's own local bound |f|/|∇f|, and away from the wall at the cut) the baked field puts
/// every point on the same side as the shape does.
#[test]
fn a_shape_without_a_bound_is_refused_and_bakes_with_the_right_sides() {
    let shape =
        "intersect { implicit { y - 0.12 * atan2(z, x) }  cylinder(radius = 0.9, height = 1.2) }";
    let refused = sdfc_compiler::check::compile(shape);
    assert!(refused.scene.is_none(), "the ramp compiled without a bound");
    let source = format!("bake(res = 48) {{ {shape} }}");
    let scene = sdfc_compiler::check::compile(&source).scene.expect("baked");
    let v = &scene.volumes()[0];
    let exact = |p: DVec3| {
        let ramp = p.y - 0.12 * p.z.atan2(p.x);
        let q = DVec3::new(
            DVec3::new(p.x, 0.0, p.z).length() - 0.9,
            p.y.abs() - 0.6,
            0.0,
        );
        let cyl = q.x.max(q.y).min(0.0) + q.max(DVec3::ZERO).length();
        ramp.max(cyl)
    };
    let (mut checked, mut wrong) = (0, 0);
    let mut r = Rng::new(36);
    for _ in 0..20_000 {
        let p = DVec3::new(r.range(-1.1, 1.1), r.range(-0.8, 0.8), r.range(-1.1, 1.1));
        // The true distance is at least |f|/|∇f| with |∇f| ≤ 1 + 0.12/ρ away from the axis;
        // points nearer than two cells to the surface (or to the axis) are not judged.
        let rho = DVec3::new(p.x, 0.0, p.z).length();
        if rho < 0.1 || exact(p).abs() / (1.0 + 0.12 / rho) < 2.0 * v.grid.h {
            continue;
        }
        // Nor beside the cut (z = 0, x < 0), whose wall that bound does not see.
        if p.x < 0.0 && p.z.abs() < 2.0 * v.grid.h {
            continue;
        }
        checked += 1;
        if (exact(p) < 0.0) != (eval::distance(&scene, p) < 0.0) {
            wrong += 1;
            println!(
                "wrong side at {p}: {} against {}",
                exact(p),
                eval::distance(&scene, p)
            );
        }
    }
    println!(
        "{checked} points judged, {wrong} on the wrong side; cell {:.4}",
        v.grid.h
    );
    // Every grid point of a finer map has the ramp's own sign (the samples' sign is the
    // stored one): no point is filled from a bound the ramp does not have.
    let fine = sdfc_compiler::check::compile(&format!("bake(res = 96) {{ {shape} }}"))
        .scene
        .expect("baked");
    let f = &fine.volumes()[0];
    let [nx, ny, nz] = f.grid.n;
    let mut flipped = 0;
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                let e = exact(f.grid.point(i, j, k));
                let stored = f.values[f.grid.index(i, j, k)];
                if e.abs() > 1e-9 && (e < 0.0) != (stored < 0.0) {
                    flipped += 1;
                }
            }
        }
    }
    assert_eq!(flipped, 0, "grid points on the wrong side at 96 points");
    assert!(checked > 5_000);
    assert_eq!(wrong, 0);
}

/// The cache's file holds the values and the grid, and reads back to the same volume (λ proven
/// again); a truncated or foreign file is not a volume.
#[test]
fn a_volume_file_reads_back_whole_or_not_at_all() {
    use sdfc_compiler::bake::file;
    let v = &volumes_of("bake(res = 16) { sphere(0.5) }")[0];
    let bytes = file::with_header(v);
    assert_eq!(file::from_header(&bytes).as_ref(), Some(v.as_ref()));
    // Off-centre boxes too: the grid read back is the one baked to the last bit (its last
    // point is not recomputed from the first), or the cache would never match it.
    for k in 1..8 {
        let source = format!(
            "bake(res = 12) {{ sphere(0.5) at ({}, {}, 0) }}",
            0.37 * f64::from(k),
            -1.9 / f64::from(k)
        );
        let v = &volumes_of(&source)[0];
        assert_eq!(
            file::from_header(&file::with_header(v)).as_ref(),
            Some(v.as_ref()),
            "{source}"
        );
    }
    assert_eq!(file::raw(v).len(), 4 * v.values.len());
    assert!(file::from_header(&bytes[..bytes.len() - 1]).is_none());
    assert!(file::from_header(b"SDFCVOL0 and more bytes than a header has, surely ....").is_none());
}

/// A shape with a distance estimate (the Mandelbulb: `Primitive::estimate`) is sampled at every
/// grid point when baked: its λ is not a proven bound, so no block is skipped on its word. The
/// map equals the one from every sample, for the fractal alone and in a union.
#[test]
fn a_shape_with_an_estimate_is_baked_from_every_point() {
    for (res, shape) in [
        // (At 33 points the square bulb's map, sampled near its surface only on its λ of 1,
        // differed from this one.)
        (33, "mandelbulb(2, 5)"),
        (33, "union { mandelbulb(2, 5)  sphere(0.4) at (0.9, 0, 0) }"),
        (40, "mandelbulb(8, 6)"),
    ] {
        let source = format!("bake(res = {res}) {{ {shape} }}");
        let scene = sdfc_compiler::check::compile(&source).scene.expect("baked");
        let v = &scene.volumes()[0];
        let unbaked = sdfc_compiler::check::compile(shape)
            .scene
            .expect("the shape");
        let field = |p: DVec3| eval::distance(&unbaked, p) * unbaked.root_node().lambda;
        let every = Volume::from_samples(v.grid, &v.grid.sample(&field), &field);
        assert!(every == **v, "{shape}: the baked map skipped points");
    }
}
