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
/// the other sign (so steps of F/λ never cross the baked surface).
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
        let res = 8 + r.below(32);
        let field = |p: DVec3| eval::distance(&scene, p);
        let v = Volume::bake(&field, DVec3::splat(-2.0), DVec3::splat(2.0), res);
        let what = format!("seed {} at {res}\n{source}", seed + i);
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
