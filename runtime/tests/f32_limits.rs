//! `implicit` fields near f32's limits (exponentials, powers, quotients and products reaching
//! 1e38, values underflowing to denormals and zero), each in a scene whose rays reach about 105
//! from the origin: the checker refuses the ones whose f32 arithmetic overflows where rays go
//! (`check/overflow.rs`), and for every one it accepts the GPU's field is finite wherever the
//! f64 reference is, at points throughout that region.

use crate::common::{gpu, report};
use sdfc::gpu::Gpu;
use sdfc_compiler::emit;
use sdfc_compiler::lower::{Entry, tracer::Options};
use sdfc_compiler::reference::eval;
use sdfc_compiler::scene::Scene;

/// Expressions and whether the checker must refuse them (`true`) for f32's range.
const CASES: &[(&str, bool)] = &[
    // Issue 31's two: exp(100) overflows; the logistic is ∞/∞ = NaN past x ≈ 88.7.
    (
        "implicit { y - exp(100 - abs(x)) * 1e-44 } @lipschitz(1.04)",
        true,
    ),
    ("implicit { y - exp(x) / (1 + exp(x)) } @lipschitz(1)", true),
    ("implicit { y - log(1 + exp(x)) } @lipschitz(1.5)", true),
    ("implicit { y - sin(exp(x)) } @lipschitz(1e30)", true),
    ("implicit { y - exp(x * 0.9) * 1e-30 } @lipschitz(2)", true),
    (
        "implicit { y - 1e18 * 1e18 * 1e3 * x * 1e-39 } @lipschitz(1.5)",
        true,
    ),
    (
        "implicit { y - (abs(x) + 1) ^ 20 * 1e-40 } @lipschitz(2)",
        true,
    ),
    // Within range everywhere rays reach (underflow to zero is harmless).
    ("implicit { y - exp(-x*x) } @lipschitz(1.5)", false),
    (
        "implicit { y - exp(x * 0.8) * 1e-36 } @lipschitz(1.5)",
        false,
    ),
    (
        "implicit { y - exp(-abs(x)) * 1e-10 } @lipschitz(1.1)",
        false,
    ),
    (
        "implicit { y - 1e18 * 1e18 * x * 1e-36 } @lipschitz(1.5)",
        false,
    ),
    (
        "implicit { y - (abs(x) + 1) ^ 18 * 1e-36 } @lipschitz(2)",
        false,
    ),
    (
        "implicit { y - 1 / (abs(x) + 1e-18) * 1e-20 } @lipschitz(1e3)",
        false,
    ),
    (
        "implicit { y - x * x * x * x * x * x * x * x * 1e-16 } @lipschitz(2)",
        false,
    ),
    (
        "implicit { length(x, y, z) * 1e36 - 1e36 } @lipschitz(1e36)",
        false,
    ),
];

/// Points throughout the box rays reach (|x|, |y|, |z| ≤ 105): a lattice, its faces, and
/// small ones near the origin.
fn points() -> Vec<glam::DVec3> {
    let mut v = Vec::new();
    let steps = [
        -105.0, -88.0, -60.0, -20.0, -1.0, -1e-3, 0.0, 1e-3, 1.0, 20.0, 60.0, 88.0, 105.0,
    ];
    for &x in &steps {
        for &y in &steps {
            for &z in &[-105.0, 0.0, 3.0, 105.0] {
                v.push(glam::DVec3::new(x, y, z));
            }
        }
    }
    v
}

fn field_at(gpu: &Gpu, scene: &Scene, points: &[glam::DVec3]) -> Vec<f32> {
    let (module, _) = emit::module(scene, Entry::Field, &Options::from_scene(scene))
        .unwrap_or_else(|e| panic!("{}", e.0));
    let p: Vec<[f32; 3]> = points.iter().map(|p| p.as_vec3().to_array()).collect();
    gpu.eval_points(&module, &p).unwrap()
}

#[test]
fn accepted_implicits_stay_finite_in_f32_where_rays_reach() {
    let gpu = gpu();
    let pts = points();
    let (mut refused, mut accepted, mut compared) = (0, 0, 0);
    for &(source, must_refuse) in CASES {
        let checked = sdfc_compiler::check::compile(source);
        // (A constant part always beyond it is refused by the Lipschitz inference already.)
        let text = sdfc_compiler::diag::render(&checked.diagnostics, "test", source);
        let overflow = checked.scene.is_none() && text.contains("f32's range");
        assert_eq!(overflow, must_refuse, "{source}: {text}");
        let Some(scene) = checked.scene else {
            assert!(must_refuse, "{source} refused for another reason");
            refused += 1;
            continue;
        };
        accepted += 1;
        let gpu_values = field_at(&gpu, &scene, &pts);
        for (p, g) in pts.iter().zip(gpu_values) {
            let cpu = eval::distance(&scene, *p);
            if cpu.is_finite() && cpu.abs() < f64::from(f32::MAX) {
                compared += 1;
                assert!(
                    g.is_finite(),
                    "{source}: the GPU gives {g} at {p} where the CPU gives {cpu}"
                );
            }
        }
    }
    report(&format!(
        "f32 limits: {refused} implicit fields refused for overflowing f32 where rays reach, {accepted} accepted, their GPU field finite at all {compared} points where the f64 one is"
    ));
}
