//! The data form's buffers and shader from the part trees (issue 33): modules that validate
//! and do not grow with the parts, every cell's program giving the whole field, the proxy
//! outside the grid a bound, and blended materials kept exact through pruning.

use crate::tape::{balls, near_tie, point, random_scene, region};
use glam::DVec3;
use sdfc_compiler::reference::eval;
use sdfc_compiler::tape::{self, cells};
use sdfc_tests::{Rng, fuzz_cases, fuzz_seed, report, scene};

/// The data form's modules (and its pre-pass's) pass naga's validator for every entry and target, and their code
/// does not grow with the parts: 10 spheres and 1000 give the same WGSL but for the grid's
/// numbers.
#[test]
fn data_form_modules_validate_and_stay_the_same_size() {
    use sdfc_compiler::emit::{self, Output, Target};
    use sdfc_compiler::lower::Entry;
    use sdfc_compiler::lower::tracer::{Form, Options};
    let mut r = Rng::new(11);
    let balls = |r: &mut Rng, n: usize| {
        format!("smooth_union(0.02) {{\n{}\n}}\nplane(y, -1.2)", balls(r, n))
    };
    let mut sizes = Vec::new();
    for source in [
        balls(&mut r, 10),
        balls(&mut r, 1000),
        random_scene(&mut r),
        random_scene(&mut r),
    ] {
        let s = scene("data.sdf", &source);
        let options = Options {
            form: Form::Data,
            ..Options::from_scene(&s)
        };
        // The pre-pass on the GPU (`lower/data/prune.rs`) validates too, and writes as WGSL.
        let (module, info, _) = emit::prune_module(&s)
            .unwrap_or_else(|e| panic!("{}\n{source}", e.0))
            .expect("a pre-pass module");
        emit::write(&module, &info, Target::Wgsl, Entry::Compute).expect("the pre-pass's WGSL");
        for entry in [Entry::Compute, Entry::Fragment, Entry::Library] {
            let (module, info) =
                emit::module(&s, entry, &options).unwrap_or_else(|e| panic!("{}\n{source}", e.0));
            let wgsl = emit::write(&module, &info, Target::Wgsl, entry).expect("WGSL");
            let Output::Text(text) = wgsl else {
                panic!("text")
            };
            assert!(text.contains("tape_eval"), "no evaluator in {entry:?}");
            if entry == Entry::Compute {
                sizes.push(text.len());
            }
        }
    }
    // (The grid's corner and cell size are literals of their own digits.)
    assert!(
        sizes[0].abs_diff(sizes[1]) < 100,
        "10 and 1000 spheres' WGSL: {sizes:?}"
    );
    report(&format!(
        "tape: data form WGSL (compute entry) {} bytes for 10 spheres, {} for 1000",
        sizes[0], sizes[1]
    ));
}

/// The buffers the host uploads (`data::data`: every cell's program, shared where equal, found
/// through its range, pruned level by level) give the whole tree's value at random points of
/// the grid, and the program outside it gives the parts the grid does not hold; a cell marked
/// far (far-field culling) has a clearance no larger than the field anywhere in it.
#[test]
fn the_data_s_programs_give_the_whole_field_in_every_cell() {
    use sdfc_compiler::tape::{data, program};
    let mut r = Rng::new(21);
    let scenes = [
        format!("smooth_union(0.03) {{\n{}\n}}\nplane(y, -1.2)", balls(&mut r, 300)),
        "subtract { box((1.6, 1.2, 1.4))  smooth_union(0.1) { sphere(0.7) at (-0.6, 0, 0)  box((0.8, 0.8, 3)) } }".to_string(),
    ];
    let mut said = Vec::new();
    for source in &scenes {
        let s = scene("cells.sdf", source);
        let (tree, layout) = data::layout(&s, None).expect("a data form");
        let d = data::data(&s, &tree, &layout).expect("its buffers");
        let table = program::Table::new(&s, &tree).expect("a table");
        let n = layout.n.map(|k| k as f64);
        let hi = layout.lo + DVec3::new(n[0], n[1], n[2]) * layout.size;
        let run = |i: usize, p: DVec3| {
            let [start, count] = d.ranges[data::HEADER + i];
            let (len, clearance) = data::unpack_count(count, layout.size);
            let words = d.code[start as usize..(start + len) as usize].to_vec();
            let code = program::Code {
                words,
                leaves: 0,
                depth: 0,
            };
            (program::run(&table, &code, p).0, clearance)
        };
        let mut far = 0;
        for _ in 0..5000 {
            let p = point(&mut r, layout.lo, hi);
            let c = ((p - layout.lo) / layout.size).floor();
            let i = c.x as usize + layout.n[0] * (c.y as usize + layout.n[1] * c.z as usize);
            let ((got, clearance), want) = (run(i, p), tape::eval::value(&s, &tree, p));
            assert!(
                (got - want).abs() <= 1e-12 * (1.0 + want.abs()),
                "at {p} (cell {c}): program {got}, tree {want}\n{source}"
            );
            if let Some(clear) = clearance {
                assert!(
                    clear <= want,
                    "at {p} (cell {c}): clearance {clear} above the field {want}"
                );
                far += 1;
            }
        }
        // Outside the grid, the parts it does not hold (the plane) where there are any.
        if let Some(outside) = data::outside(&s, &tree) {
            let p = hi + DVec3::new(0.5, 0.7, 0.3);
            let want = tape::eval::value(&s, &outside, p);
            assert!((run(d.cells(), p).0 - want).abs() <= 1e-12 * (1.0 + want.abs()));
        }
        said.push(format!(
            "{}×{}×{} cells, {:.1} leaves a cell, {far} of 5000 points in far cells",
            layout.n[0], layout.n[1], layout.n[2], d.mean_leaves
        ));
    }
    report(&format!(
        "tape: the data's programs give the field in every cell: {}",
        said.join("; ")
    ));
}

/// Outside the grid the data form takes the distance to the grid's box plus its margin as a
/// bound for the parts inside it: the whole field is never below it there — also where a
/// parameter in a turn leaves the scene's own box unknown (the grid then holds the leaves'
/// boxes, grown by every blend radius: two cubes blended with k = 0.8, one turned, bulge
/// beyond their boxes by more than the twentieth the grid grows by — without the blend radii
/// this test fails there).
#[test]
fn the_proxy_outside_the_grid_is_a_bound() {
    use sdfc_compiler::tape::data;
    use std::collections::HashMap;
    let mut r = Rng::new(5);
    let scenes = [
        format!(
            "param a = 45deg\nsmooth_union(0.05) {{\n{}\nbox((0.5, 0.1, 0.1)) |> rotate(z, a) at (0, 0, -0.9)\n}}",
            balls(&mut r, 40)
        ),
        "param a = 0deg\nsmooth_union(0.8) { box((0.4, 0.4, 0.4)) |> rotate(z, a) at (-0.5, 0, 0)  box((0.4, 0.4, 0.4)) at (0.5, 0, 0) }".to_string(),
    ];
    let values = HashMap::from([("a".to_string(), vec![100f64.to_radians()])]);
    let mut checked = 0;
    for source in &scenes {
        let s = scene("proxy.sdf", source).with_values(&values);
        let (tree, layout) = data::layout(&s, None).expect("a data form");
        assert!(data::outside(&s, &tree).is_none(), "{source}");
        let margin = layout.proxy.expect("a proxy: every part is finite");
        let n = layout.n.map(|k| k as f64);
        let hi = layout.lo + DVec3::new(n[0], n[1], n[2]) * layout.size;
        let (lo, extent) = (layout.lo, (hi - layout.lo).max_element());
        for _ in 0..20_000 {
            let p = point(&mut r, lo - DVec3::splat(extent), hi + DVec3::splat(extent));
            let outside = (p - hi).max(lo - p).max(DVec3::ZERO).length();
            if outside == 0.0 {
                continue;
            }
            let whole = tape::eval::value(&s, &tree, p);
            assert!(
                whole >= outside + margin - 1e-9,
                "at {p}: the field {whole} is below the proxy {}\n{source}",
                outside + margin
            );
            checked += 1;
        }
    }
    report(&format!(
        "tape: the proxy outside the grid bounds the field at {checked} points (a turned part's parameter; cubes blended with k = 0.8)"
    ));
}

/// A blend as shading sees it: one material where both are the same or the weight is 0 or 1.
fn shown(b: sdfc_compiler::reference::blend::Blend) -> sdfc_compiler::reference::blend::Blend {
    use sdfc_compiler::reference::blend::Blend;
    match b {
        Blend { a, b, .. } if a == b => Blend::plain(a),
        Blend { a, t, .. } if t <= 0.0 => Blend::plain(a),
        Blend { b, t, .. } if t >= 1.0 => Blend::plain(b),
        b => b,
    }
}

/// Materials blended through smooth folds (`tape::eval::blend`, the f64 twin of the shader's
/// `tape_blend`) are the reference's (`reference::eval::blend`: two ids, a weight) for the
/// whole tree at random points of random trees, and a cell's pruned tree gives the whole
/// tree's blend bit for bit inside the cell — material propagation through pruning, blends
/// included.
#[test]
fn blended_materials_survive_pruning() {
    let seed = fuzz_seed(34);
    let cases = fuzz_cases(120);
    let mut r = Rng::new(seed);
    let (mut points, mut seams) = (0usize, 0usize);
    for case in 0..cases {
        let source = random_scene(&mut r);
        let s = scene("blend.sdf", &source);
        let tree = tape::build(&s).expect("a tree");
        let (lo, hi) = region(&s);
        for _ in 0..40 {
            let p = point(&mut r, lo, hi);
            if near_tie(&s, p) {
                continue;
            }
            let (_, ours) = tape::eval::blend(&s, &tree, p);
            let (ours, want) = (shown(ours), shown(eval::blend(&s, p)));
            assert!(
                ours.a == want.a && ours.b == want.b && (ours.t - want.t).abs() <= 1e-9,
                "seed {seed} case {case}: at {p}: tree {ours:?}, reference {want:?}\n{source}"
            );
            seams += usize::from(ours.t > 0.0 && ours.t < 1.0 && ours.a != ours.b);
        }
        for _ in 0..6 {
            let size = (hi - lo).max_element() * r.range(0.01, 0.4);
            let center = point(&mut r, lo, hi);
            let pruned = cells::prune(&s, &tree, center, size * 3f64.sqrt() / 2.0);
            for _ in 0..30 {
                let half = DVec3::splat(size / 2.0);
                let p = point(&mut r, center - half, center + half);
                let (_, whole) = tape::eval::blend(&s, &tree, p);
                let (_, part) = tape::eval::blend(&s, &pruned, p);
                assert!(
                    whole.a == part.a && whole.b == part.b && whole.t.to_bits() == part.t.to_bits(),
                    "seed {seed} case {case}: at {p} in the cell at {center}: whole {whole:?}, \
                     pruned {part:?}\n{source}"
                );
                points += 1;
            }
        }
    }
    assert!(seams > 0, "no point fell in a seam: the test saw no blend");
    report(&format!(
        "tape: {cases} random trees (seed {seed}): blended materials equal the reference's \
         ({seams} points in a seam of two materials) and the pruned trees' at {points} points in cells"
    ));
}
