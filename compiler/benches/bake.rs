//! Distance-map baking benchmark (criterion): `bake::Volume::bake` of the primitives example's
//! field (its exact CPU evaluator) over the box ±2.5 at 32, 64 and 128 points per side — the
//! sampling, the vector propagation and the λ of the interpolant. `cargo bench -p
//! sdfc-compiler --bench bake`.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use glam::DVec3;
use sdfc_compiler::bake::Volume;
use sdfc_compiler::reference::eval;

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("bake");
    g.sample_size(10);
    let path = format!("{}/../examples/primitives.sdf", env!("CARGO_MANIFEST_DIR"));
    let source = std::fs::read_to_string(path).expect("example");
    let scene = sdfc_compiler::check::compile(&source)
        .scene
        .expect("checks");
    let field = |p: DVec3| eval::distance(&scene, p);
    for res in [32, 64, 128] {
        g.bench_with_input(BenchmarkId::new("primitives", res), &res, |b, &res| {
            b.iter(|| Volume::bake(&field, DVec3::splat(-2.5), DVec3::splat(2.5), res).lambda)
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
