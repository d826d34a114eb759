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
pub(crate) fn point(r: &mut Rng, lo: DVec3, hi: DVec3) -> DVec3 {
    DVec3::new(
        r.range(lo.x, hi.x),
        r.range(lo.y, hi.y),
        r.range(lo.z, hi.z),
    )
}

/// Where to sample a scene: its finite bound grown by half, else a box around the origin.
pub(crate) fn region(scene: &Scene) -> (DVec3, DVec3) {
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
pub(crate) fn near_tie(scene: &Scene, p: DVec3) -> bool {
    let m = eval::sample(scene, p).mat;
    [DVec3::X, DVec3::Y, DVec3::Z].iter().any(|&e| {
        eval::sample(scene, p + e * 1e-7).mat != m || eval::sample(scene, p - e * 1e-7).mat != m
    })
}

/// A random tree's source: folds of up to four children, two or three levels deep, over
/// spheres, boxes, tori and capsules, moved, turned and scaled, some with materials.
pub(crate) fn random_scene(r: &mut Rng) -> String {
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
pub(crate) fn balls(r: &mut Rng, n: usize) -> String {
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
