//! The scene as data (`sdfc_compiler::tape`): its tree evaluates as the reference evaluator does,
//! and pruned to a cell it gives the whole tree's value and material inside the cell, bit for
//! bit — on the examples it holds and on random trees of hard and smooth unions,
//! intersections and subtractions of moved, turned and scaled primitives.

use glam::DVec3;
use sdfc_compiler::reference::eval;
use sdfc_compiler::scene::Scene;
use sdfc_compiler::tape::{self, Part, cells};
use sdfc_tests::{Rng, examples, fuzz_cases, fuzz_seed, report, scene};

/// A random point in the box from `lo` to `hi`.
fn point(r: &mut Rng, lo: DVec3, hi: DVec3) -> DVec3 {
    DVec3::new(
        r.range(lo.x, hi.x),
        r.range(lo.y, hi.y),
        r.range(lo.z, hi.z),
    )
}

/// Where to sample a scene: its finite bound grown by half, else a box around the origin.
fn region(scene: &Scene) -> (DVec3, DVec3) {
    let b = scene.root_node().bound;
    // (An intersection of parts that do not meet has an empty box.)
    if b.lo.is_finite() && b.hi.is_finite() && b.lo.cmplt(b.hi).all() {
        let grow = (b.hi - b.lo) * 0.5 + DVec3::splat(0.1);
        (b.lo - grow, b.hi + grow)
    } else {
        (DVec3::splat(-4.0), DVec3::splat(4.0))
    }
}

/// The tree's value and material at `p` against the reference's: values within 1e-9
/// (relative; its frames are matrices, the reference's steps), materials equal away from ties.
fn agrees(scene: &Scene, tree: &Part, p: DVec3) -> Result<(), String> {
    let (d, m) = tape::eval::sample(scene, tree, p);
    let s = eval::sample(scene, p);
    if (d - s.d).abs() > 1e-9 * (1.0 + s.d.abs()) {
        return Err(format!("at {p}: tree {d}, reference {}", s.d));
    }
    if m != s.mat {
        return Err(format!(
            "at {p}: tree's material {m:?}, reference's {:?}",
            s.mat
        ));
    }
    Ok(())
}

#[test]
fn the_examples_trees_evaluate_as_the_reference_does() {
    let mut held = Vec::new();
    let mut not = Vec::new();
    for path in examples() {
        let s = sdfc_tests::example(&path);
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        match tape::build(&s) {
            Ok(tree) => {
                let mut r = Rng::new(7);
                let (lo, hi) = region(&s);
                for _ in 0..500 {
                    let p = point(&mut r, lo, hi);
                    if let Err(e) = agrees(&s, &tree, p) {
                        // A tie between two children's values may pick either material.
                        assert!(!e.contains("material") || near_tie(&s, p), "{name}: {e}");
                    }
                }
                held.push(name);
            }
            Err(u) => not.push(format!("{name} ({})", u.what)),
        }
    }
    assert!(held.len() >= 3, "held: {held:?}; not: {not:?}");
    report(&format!(
        "tape: {} examples' trees evaluate as the reference ({}); not held yet: {}",
        held.len(),
        held.join(", "),
        not.join(", ")
    ));
}

/// Whether `p` is where the material may flip on rounding: the reference's value changes
/// material within 1e-9 of it.
fn near_tie(scene: &Scene, p: DVec3) -> bool {
    let m = eval::sample(scene, p).mat;
    [DVec3::X, DVec3::Y, DVec3::Z].iter().any(|&e| {
        eval::sample(scene, p + e * 1e-7).mat != m || eval::sample(scene, p - e * 1e-7).mat != m
    })
}

/// A random tree's source: folds of up to four children, two or three levels deep, over
/// spheres, boxes, tori and capsules, moved, turned and scaled, some with materials.
fn random_scene(r: &mut Rng) -> String {
    let mut text = String::from(
        "material a { color #ff0000 }\nmaterial b { color #00ff00 }\nmaterial c { color #0000ff }\n",
    );
    text += &shape(r, 3);
    text
}

fn shape(r: &mut Rng, depth: u32) -> String {
    let leaf = depth == 0 || r.below(3) == 0;
    let mut s = if leaf {
        match r.below(4) {
            0 => format!("sphere({:.3})", r.range(0.1, 0.8)),
            1 => format!(
                "box(({:.3}, {:.3}, {:.3}))",
                r.range(0.1, 1.0),
                r.range(0.1, 1.0),
                r.range(0.1, 1.0)
            ),
            2 => format!(
                "torus({:.3}, {:.3})",
                r.range(0.3, 0.8),
                r.range(0.05, 0.25)
            ),
            _ => format!(
                "capsule({:.3}, {:.3})",
                r.range(0.2, 1.0),
                r.range(0.05, 0.3)
            ),
        }
    } else {
        let op = *r.pick(&[
            "union",
            "smooth_union",
            "intersect",
            "smooth_intersect",
            "subtract",
            "smooth_subtract",
        ]);
        let k = if op.starts_with("smooth") {
            format!("({:.3})", r.range(0.02, 0.5))
        } else {
            String::new()
        };
        let n = 2 + r.below(3);
        let children: Vec<String> = (0..n).map(|_| shape(r, depth - 1)).collect();
        format!("{op}{k} {{\n{}\n}}", children.join("\n"))
    };
    if r.below(3) == 0 {
        s = format!(
            "{s} |> rotate(({:.2}, {:.2}, {:.2}), {:.0}deg)",
            r.range(-1.0, 1.0),
            r.range(-1.0, 1.0),
            r.range(0.1, 1.0),
            r.range(-180.0, 180.0)
        );
    }
    if r.below(4) == 0 {
        s = format!("{s} |> scale({:.2})", r.range(0.5, 2.0));
    }
    if r.below(2) == 0 {
        s = format!(
            "{s} at ({:.2}, {:.2}, {:.2})",
            r.range(-1.0, 1.0),
            r.range(-1.0, 1.0),
            r.range(-1.0, 1.0)
        );
    }
    if r.below(4) == 0 {
        s = format!("{s} : {}", r.pick(&["a", "b", "c"]));
    }
    s
}

#[test]
fn pruned_trees_equal_the_whole_inside_their_cells() {
    let seed = fuzz_seed(33);
    let cases = fuzz_cases(150);
    let mut r = Rng::new(seed);
    let (mut leaves, mut kept, mut points) = (0usize, 0usize, 0usize);
    for case in 0..cases {
        let source = random_scene(&mut r);
        let s = scene("tape.sdf", &source);
        let tree =
            tape::build(&s).unwrap_or_else(|u| panic!("seed {seed} case {case}: {u:?}\n{source}"));
        let (lo, hi) = region(&s);
        for _ in 0..8 {
            let size = (hi - lo).max_element() * r.range(0.01, 0.4);
            let center = point(&mut r, lo, hi);
            let radius = size * 3f64.sqrt() / 2.0;
            let pruned = cells::prune(&s, &tree, center, radius);
            leaves += tree.leaves();
            kept += pruned.leaves();
            for _ in 0..40 {
                let half = DVec3::splat(size / 2.0);
                let p = point(&mut r, center - half, center + half);
                let whole = tape::eval::sample(&s, &tree, p);
                let part = tape::eval::sample(&s, &pruned, p);
                assert!(
                    whole.0.to_bits() == part.0.to_bits() && whole.1 == part.1,
                    "seed {seed} case {case}: at {p} in the cell at {center} of size {size}: \
                     whole {whole:?}, pruned {part:?}\n{source}"
                );
                points += 1;
            }
            // Pruned again for a quarter of the cell, from the cell's pruned tree (as the grid's
            // levels are: `cells::map_grid`): still the whole tree's field in there.
            let quarter = size / 4.0;
            let corner = center - DVec3::splat(size / 2.0);
            let sub = corner
                + (DVec3::new(r.below(4) as f64, r.below(4) as f64, r.below(4) as f64) + 0.5)
                    * quarter;
            let inner = cells::prune(&s, &pruned, sub, quarter * 3f64.sqrt() / 2.0);
            for _ in 0..10 {
                let half = DVec3::splat(quarter / 2.0);
                let p = point(&mut r, sub - half, sub + half);
                let whole = tape::eval::sample(&s, &tree, p);
                let part = tape::eval::sample(&s, &inner, p);
                assert!(
                    whole.0.to_bits() == part.0.to_bits() && whole.1 == part.1,
                    "seed {seed} case {case}: at {p} in the sub-cell at {sub} of size {quarter}: \
                     whole {whole:?}, pruned twice {part:?}\n{source}"
                );
                points += 1;
            }
        }
    }
    report(&format!(
        "tape: {cases} random trees (seed {seed}), {points} points in random cells and their \
         sub-cells pruned from them: the pruned tree's value and material equal the whole tree's \
         bit for bit; the cells kept {:.1}% of the leaves",
        100.0 * kept as f64 / leaves as f64
    ));
}

/// `n` balls of radius 0.02 to 0.06 in the box from −1 to 1, a line each.
fn balls(r: &mut Rng, n: usize) -> String {
    let lines: Vec<String> = (0..n)
        .map(|_| {
            let c = point(r, DVec3::splat(-1.0), DVec3::splat(1.0));
            let radius = r.range(0.02, 0.06);
            format!(
                "sphere({radius:.3}) at ({:.3}, {:.3}, {:.3})",
                c.x, c.y, c.z
            )
        })
        .collect();
    lines.join("\n")
}

/// Unions of many spheres, hard and smooth: a 16³ grid over them keeps a few leaves per cell.
#[test]
fn a_cell_of_a_large_union_keeps_a_few_leaves() {
    let mut r = Rng::new(5);
    let n = 1000;
    let balls = balls(&mut r, n);
    let mut said = Vec::new();
    for op in ["union", "smooth_union(0.03)"] {
        let s = scene("balls.sdf", &format!("{op} {{\n{balls}\n}}"));
        let tree = tape::build(&s).expect("a union of spheres");
        let grid = cells::Cells::new(&s, &tree, DVec3::splat(-1.1), 2.2 / 16.0, [16; 3]);
        let mean = grid.mean_leaves();
        assert!(mean < n as f64 / 20.0, "{op}: {mean} leaves a cell of {n}");
        // And inside the cells the pruned trees give the field.
        for _ in 0..2000 {
            let p = point(&mut r, DVec3::splat(-1.1), DVec3::splat(1.1));
            let cell = grid.at(p).expect("inside the grid");
            assert_eq!(
                tape::eval::value(&s, cell, p).to_bits(),
                tape::eval::value(&s, &tree, p).to_bits(),
                "{op} at {p}"
            );
        }
        said.push(format!("{op}: {mean:.1} of {n} leaves a cell"));
    }
    report(&format!(
        "tape: 16³ cells over 1000 spheres: {}",
        said.join("; ")
    ));
}

/// `cells::keep` alone: for random operands within random bounds, folding only the kept ones
/// gives the fold of all of them, bit for bit, and picks the same operand as the nearest
/// (farthest) — minimum and maximum, sharp and smooth.
#[test]
fn kept_operands_fold_to_the_whole_fold() {
    use sdfc_compiler::tape::Way;
    use sdfc_compiler::tape::eval::combine;
    let mut r = Rng::new(fuzz_seed(36));
    let fold = |way: Way, k: f64, values: &[(usize, f64)]| {
        let (mut acc, mut best) = (values[0].1, values[0]);
        for &(i, v) in &values[1..] {
            acc = combine(way, k, acc, v);
            let better = match way {
                Way::Min => v < best.1,
                Way::Max => v > best.1,
            };
            if better {
                best = (i, v);
            }
        }
        (acc.to_bits(), best.0)
    };
    for case in 0..fuzz_cases(20_000) {
        let way = if r.below(2) == 0 { Way::Min } else { Way::Max };
        let k = if r.below(3) == 0 {
            0.0
        } else {
            r.range(0.05, 1.0)
        };
        let n = 2 + r.below(7);
        let bounds: Vec<(f64, f64)> = (0..n)
            .map(|_| {
                let (v, w) = (r.range(-2.0, 2.0), r.range(0.0, 0.3) * r.below(2) as f64);
                (v - w, v + w)
            })
            .collect();
        let kept = cells::keep(way, k, &bounds);
        for _ in 0..8 {
            let values: Vec<(usize, f64)> = bounds
                .iter()
                .enumerate()
                .map(|(i, &(lo, hi))| (i, r.range(lo, hi)))
                .collect();
            let some: Vec<(usize, f64)> = kept.iter().map(|&i| values[i]).collect();
            assert_eq!(
                fold(way, k, &values),
                fold(way, k, &some),
                "case {case}: {way:?} k {k} bounds {bounds:?} kept {kept:?} values {values:?}"
            );
        }
    }
}

/// The program (the words the shader will read) run by `program::run` gives the tree's value
/// (within 1e-12: its frames are summed by rows) and material, for random trees whole and
/// pruned to random cells; its stack stays within `MAX_STACK`; leaves counted alike.
#[test]
fn programs_run_as_their_trees_evaluate() {
    use sdfc_compiler::tape::program;
    let seed = fuzz_seed(0x7a9e);
    let mut r = Rng::new(seed);
    let (mut words, mut programs, mut deepest) = (0usize, 0usize, 0usize);
    for case in 0..fuzz_cases(100) {
        let source = random_scene(&mut r);
        let s = scene("tape.sdf", &source);
        let tree = tape::build(&s).expect("a tree");
        let (lo, hi) = region(&s);
        let table = program::Table::new(&s, &tree).expect("a table");
        for cell in 0..4 {
            let (center, size) = (
                point(&mut r, lo, hi),
                (hi - lo).max_element() * r.range(0.05, 0.5),
            );
            let t = if cell == 0 {
                tree.clone()
            } else {
                cells::prune(&s, &tree, center, size * 0.87)
            };
            let prog = program::encode(&table, &t).expect("a program");
            assert_eq!(prog.leaves, t.leaves());
            (words, programs, deepest) = (
                words + prog.words.len(),
                programs + 1,
                deepest.max(prog.depth),
            );
            for _ in 0..30 {
                let half = DVec3::splat(size / 2.0);
                let p = if cell == 0 {
                    point(&mut r, lo, hi)
                } else {
                    point(&mut r, center - half, center + half)
                };
                let (want, want_m) = tape::eval::sample(&s, &t, p);
                let (got, got_m) = program::run(&table, &prog, p);
                assert!(
                    (got - want).abs() <= 1e-12 * (1.0 + want.abs()),
                    "seed {seed} case {case} at {p}: program {got}, tree {want}\n{source}"
                );
                assert!(
                    got_m == want_m || near_tie(&s, p),
                    "seed {seed} case {case} at {p}: materials {got_m:?} {want_m:?}\n{source}"
                );
            }
        }
    }
    report(&format!(
        "tape programs: {programs} programs of random trees and cells (seed {seed}) run as their \
         trees evaluate; {:.0} instructions (4 bytes) a program, stack at most {deepest}",
        words as f64 / programs as f64
    ));
}

/// The data form's modules pass naga's validator for every entry and target, and their code
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
/// the grid, and the program outside it gives the parts the grid does not hold.
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
            let [start, len] = d.ranges[data::HEADER + i];
            let words = d.code[start as usize..(start + len) as usize].to_vec();
            let code = program::Code {
                words,
                leaves: 0,
                depth: 0,
            };
            program::run(&table, &code, p).0
        };
        for _ in 0..5000 {
            let p = point(&mut r, layout.lo, hi);
            let c = ((p - layout.lo) / layout.size).floor();
            let i = c.x as usize + layout.n[0] * (c.y as usize + layout.n[1] * c.z as usize);
            let (got, want) = (run(i, p), tape::eval::value(&s, &tree, p));
            assert!(
                (got - want).abs() <= 1e-12 * (1.0 + want.abs()),
                "at {p} (cell {c}): program {got}, tree {want}\n{source}"
            );
        }
        // Outside the grid, the parts it does not hold (the plane) where there are any.
        if let Some(outside) = data::outside(&s, &tree) {
            let p = hi + DVec3::new(0.5, 0.7, 0.3);
            let want = tape::eval::value(&s, &outside, p);
            assert!((run(d.cells(), p) - want).abs() <= 1e-12 * (1.0 + want.abs()));
        }
        said.push(format!(
            "{}×{}×{} cells, {:.1} leaves a cell",
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
