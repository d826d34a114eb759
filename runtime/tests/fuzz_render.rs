//! Random valid scenes (the compiler fuzzer's generator, `sdfc_tests::scenes`) rendered on the
//! GPU: each checked scene's shader is either refused by the compile limit or drawn at 8×6 with
//! every depth and normal finite; how long each took against its predicted compile is
//! printed (not asserted: timing belongs in benchmarks), with the count. A new seed each CI
//! run (`sdfc_tests::fuzz_seed`), `SDFC_FUZZ_RENDERS` scenes (default 100) for runs by hand.

use crate::common::{gpu, report};
use sdfc_compiler::cost;
use sdfc_compiler::emit;
use sdfc_compiler::lower::{Entry, tracer::Options};
use sdfc_compiler::view::View;

/// Scenes generated in CI (about two in three check; each render compiles a new shader).
const RENDERS: u64 = 100;

#[test]
fn random_valid_scenes_render_finitely_or_are_refused_by_the_compile_limit() {
    let cases: u64 = sdfc_tests::env_number("SDFC_FUZZ_RENDERS").unwrap_or(RENDERS);
    let seed = sdfc_tests::fuzz_seed(0x5dfc_4e4d);
    let gpu = gpu();
    let (mut checked, mut drawn, mut refused) = (0, 0, 0);
    // The render that took longest against its prediction's upper end: (ratio, seconds,
    // predicted seconds, seed of the scene).
    let mut worst = (0.0f64, 0.0, 0.0, 0);
    let mut slowest = 0.0f64;
    for i in 0..cases {
        let case = seed.wrapping_add(i.wrapping_mul(0x9e37_79b9_7f4a_7c15)) | 1;
        let source = sdfc_tests::scenes::scene(case);
        let scene = {
            let s = source.clone();
            sdfc_tests::with_stack(move || sdfc_compiler::check::compile(&s).scene)
        };
        let Some(scene) = scene else { continue };
        checked += 1;
        let clock = std::time::Instant::now();
        let (module, _) = emit::module(&scene, Entry::Compute, &Options::from_scene(&scene))
            .unwrap_or_else(|e| panic!("invalid module for\n{source}\n{}", e.0));
        let predicted = cost::predict_module(&module);
        if predicted.too_slow() {
            refused += 1;
            continue;
        }
        gpu.set_scene(&scene);
        let view = View::new(&scene.camera, 8, 6);
        let frame = gpu
            .render(&module, &view, None, |_, _| {})
            .unwrap_or_else(|e| panic!("render failed: {e}\n{source}"));
        let seconds = clock.elapsed().as_secs_f64();
        drawn += 1;
        let finite = frame.depth.iter().all(|d| d.is_finite())
            && frame.normal.iter().flatten().all(|c| c.is_finite());
        assert!(
            finite,
            "a non-finite depth or normal for seed {case}:\n{source}"
        );
        slowest = slowest.max(seconds);
        let ratio = seconds / predicted.at_most.max(1e-3);
        if seconds > 1.0 && ratio > worst.0 {
            worst = (ratio, seconds, predicted.seconds, case);
        }
    }
    let against = if worst.3 == 0 {
        "none took over 1 s".to_string()
    } else {
        format!(
            "of those over 1 s, the longest against its prediction's upper end took {:.2}× it ({:.1} s, predicted {:.1} s, scene seed {})",
            worst.0, worst.1, worst.2, worst.3
        )
    };
    let line = format!(
        "render fuzzer: {cases} scenes, {checked} checked, {drawn} drawn (every depth and normal finite), {refused} refused by the compile limit; slowest {slowest:.1} s (compile and render); {against}"
    );
    report(&line);
    assert!(checked > 0, "no scene checked");
}
