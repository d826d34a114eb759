//! Compile-time benchmark (criterion): parse → check → lower → validate → emit WGSL for
//! generated scenes of about 10, 100, 1 000 and 10 000 nodes. `cargo bench -p sdfc-compiler`.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use sdfc_compiler::emit::{self, Output, Target};
use sdfc_compiler::lower::{Entry, tracer::Options};

/// A scene of `groups` smooth unions of four shapes each, every shape moved (`at`) and some
/// rotated, under one union: about 10 nodes per group (each `at` and rotation is a node).
fn scene(groups: usize) -> String {
    let mut s = String::from("camera { eye (0, 4, -12) target (0, 0, 0) }\nunion {\n");
    for g in 0..groups {
        let (x, z) = ((g % 32) as f64 * 0.7, (g / 32) as f64 * 0.7);
        s += &format!(
            "  smooth_union(0.1) {{\n    sphere(0.2) at ({x}, 0.2, {z})\n    box(0.3) |> rotate(y, {g}deg) at ({x}, 0.5, {z})\n    torus(0.25, 0.05) at ({x}, 0.8, {z})\n    cylinder(0.05, 0.6) at ({x}, 0.3, {z})\n  }}\n"
        );
    }
    s + "}\n"
}

fn compile(source: &str) -> usize {
    let checked = sdfc_compiler::check::compile(source);
    let scene = checked.scene.expect("the generated scene checks");
    let (module, info) =
        emit::module(&scene, Entry::Compute, &Options::from_scene(&scene)).expect("valid");
    match emit::write(&module, &info, Target::Wgsl, Entry::Compute).expect("emits") {
        Output::Text(t) => t.len(),
        Output::Binary(b) => b.len(),
    }
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("compile to WGSL");
    g.sample_size(10);
    for groups in [1, 10, 100, 1000] {
        let source = scene(groups);
        let nodes = sdfc_compiler::check::compile(&source)
            .scene
            .map_or(0, |s| s.reachable().len());
        g.bench_with_input(BenchmarkId::new("nodes", nodes), &source, |b, s| {
            b.iter(|| compile(s))
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
