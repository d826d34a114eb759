//! `fidget-mesh-harness DEPTH [REPEAT]`: meshes each comparison shape with fidget at octree
//! depth DEPTH (2^DEPTH cells a side over [-1, 1]³, fidget's default view), the fastest of
//! REPEAT runs, and prints one line per shape: name, seconds, triangles, vertices, and the
//! largest and RMS distance of the vertices to the exact surface, and the largest of the
//! triangles' centroids (our own exact distance functions below, in f64).

use fidget::context::Tree;
use fidget::jit::JitShape;
use fidget::mesh::{Octree, Settings};
use std::time::Instant;

/// Exact signed distance to a box of half-size `b` at the origin.
fn box_exact(p: [f64; 3], b: [f64; 3]) -> f64 {
    let q = [p[0].abs() - b[0], p[1].abs() - b[1], p[2].abs() - b[2]];
    let out = (q[0].max(0.0).powi(2) + q[1].max(0.0).powi(2) + q[2].max(0.0).powi(2)).sqrt();
    out + q[0].max(q[1]).max(q[2]).min(0.0)
}

fn len(p: [f64; 3]) -> f64 {
    (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt()
}

/// Rotation of `p` by `a` radians about y then by `b` about x, inverted (the field's argument).
fn unturn(p: [f64; 3], a: f64, b: f64) -> [f64; 3] {
    // Undo the x rotation, then the y rotation.
    let (s, c) = (-b).sin_cos();
    let q = [p[0], c * p[1] - s * p[2], s * p[1] + c * p[2]];
    let (s, c) = (-a).sin_cos();
    [c * q[0] + s * q[2], q[1], -s * q[0] + c * q[2]]
}

fn tree_box(x: Tree, y: Tree, z: Tree, b: [f64; 3]) -> Tree {
    // The box as fidget's examples write it: max of the slabs (its zero set is the box's).
    (x.abs() - b[0]).max(y.abs() - b[1]).max(z.abs() - b[2])
}

fn turn_tree(a: f64, b: f64) -> (Tree, Tree, Tree) {
    let (x, y, z) = (Tree::x(), Tree::y(), Tree::z());
    let (s, c) = (-b).sin_cos();
    let (y1, z1) = (y.clone() * c - z.clone() * s, y * s + z * c);
    let (s, c) = (-a).sin_cos();
    (x.clone() * c + z1.clone() * s, y1, -(x * s) + z1 * c)
}

struct Shape {
    name: &'static str,
    tree: Tree,
    exact: fn([f64; 3]) -> f64,
}

const BOX: [f64; 3] = [0.8, 0.48, 0.64];
/// The same box smaller, its corners (0.99 from the centre) inside [-1, 1]³: no cut, so
/// neither mesher meets the box's sides (sdfc caps a cut; fidget's mesh stops open there).
const WHOLE: [f64; 3] = [0.7, 0.42, 0.56];
const A: f64 = 30.0 * std::f64::consts::PI / 180.0;
const B: f64 = 20.0 * std::f64::consts::PI / 180.0;

fn shapes() -> Vec<Shape> {
    let (x, y, z) = (Tree::x(), Tree::y(), Tree::z());
    let r = (x.clone().square() + y.clone().square() + z.clone().square()).sqrt();
    let (tx, ty, tz) = turn_tree(A, B);
    let (tx2, ty2, tz2) = turn_tree(A, B);
    let ring = (x.clone().square() + z.clone().square()).sqrt() - 0.72;
    vec![
        Shape {
            name: "ball",
            tree: r.clone() - 0.8,
            exact: |p| len(p) - 0.8,
        },
        Shape {
            name: "turned box",
            tree: tree_box(tx, ty, tz, BOX),
            exact: |p| box_exact(unturn(p, A, B), BOX),
        },
        Shape {
            name: "whole turned box",
            tree: tree_box(tx2, ty2, tz2, WHOLE),
            exact: |p| box_exact(unturn(p, A, B), WHOLE),
        },
        Shape {
            name: "box less a ball",
            tree: tree_box(x.clone(), y.clone(), z.clone(), [0.8; 3]).max(-(r - 0.48)),
            exact: |p| box_exact(p, [0.8; 3]).max(-(len(p) - 0.48)),
        },
        Shape {
            name: "torus",
            tree: (ring.square() + y.square()).sqrt() - 0.24,
            exact: |p| {
                let q = (p[0] * p[0] + p[2] * p[2]).sqrt() - 0.72;
                (q * q + p[1] * p[1]).sqrt() - 0.24
            },
        },
    ]
}

fn main() {
    let mut args = std::env::args().skip(1);
    let depth: u8 = args.next().and_then(|a| a.parse().ok()).expect("DEPTH");
    let repeat: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(3);
    for s in shapes() {
        let shape = JitShape::from(s.tree.clone());
        let settings = Settings {
            depth,
            ..Default::default()
        };
        let mut best = f64::INFINITY;
        let mut mesh = None;
        for _ in 0..repeat {
            let start = Instant::now();
            let octree = Octree::build(&shape, &settings).expect("built");
            let m = octree.walk_dual();
            best = best.min(start.elapsed().as_secs_f64());
            mesh = Some(m);
        }
        let m = mesh.unwrap();
        let d: Vec<f64> = m
            .vertices
            .iter()
            .map(|v| (s.exact)([v.x as f64, v.y as f64, v.z as f64]).abs())
            .collect();
        let max = d.iter().copied().fold(0.0, f64::max);
        let rms = (d.iter().map(|x| x * x).sum::<f64>() / d.len().max(1) as f64).sqrt();
        // The triangles' centroids: how far the mesh's faces (not only its vertices) lie.
        let c: Vec<f64> = m
            .triangles
            .iter()
            .map(|t| {
                let v = |i: usize| m.vertices[t[i]];
                let p = (v(0) + v(1) + v(2)) / 3.0;
                (s.exact)([p.x as f64, p.y as f64, p.z as f64]).abs()
            })
            .collect();
        let face_max = c.iter().copied().fold(0.0, f64::max);
        println!(
            "{}\t{best:.3}\t{}\t{}\t{max:.2e}\t{rms:.2e}\t{face_max:.2e}",
            s.name,
            m.triangles.len(),
            m.vertices.len()
        );
    }
}
