//! CPU evaluator benchmark (criterion): the field of `examples/bench/village_flat_apart.sdf` (39 parts
//! in one union) and of the composition at 4 096 points along camera rays, with the unions'
//! bounding-volume trees (`catalog::prune`) and without. `cargo bench -p sdfc-compiler --bench
//! eval`.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use glam::DVec3;
use sdfc_compiler::reference::eval;
use sdfc_compiler::view::View;

/// Points along a 64×64 grid of camera rays, each at a distance spread over the scene.
fn points(scene: &sdfc_compiler::scene::Scene) -> Vec<DVec3> {
    let view = View::new(&scene.camera, 64, 64);
    let mut out = Vec::new();
    for y in 0..64 {
        for x in 0..64 {
            let t = 2.0 + ((x * 7 + y * 13) % 40) as f64 * 0.5;
            out.push(view.eye + view.ray(x as f64 + 0.5, y as f64 + 0.5) * t);
        }
    }
    out
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("CPU field");
    g.sample_size(10);
    for name in ["bench/village_flat_apart", "composition"] {
        let path = format!("{}/../examples/{name}.sdf", env!("CARGO_MANIFEST_DIR"));
        let source = std::fs::read_to_string(path).expect("example");
        let scene = sdfc_compiler::check::compile(&source)
            .scene
            .expect("checks");
        let plain = scene.without_bounding_volumes();
        let pts = points(&scene);
        for (label, s) in [("with trees", &scene), ("without", &plain)] {
            g.bench_with_input(BenchmarkId::new(label, name), &pts, |b, pts| {
                b.iter(|| pts.iter().map(|&p| eval::distance(s, p)).sum::<f64>())
            });
        }
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
