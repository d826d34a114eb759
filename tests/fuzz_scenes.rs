//! Random *valid* scenes from the catalog (every primitive and operator, parameters including
//! extreme ones, nesting): each must compile to a module naga validates, whose SPIR-V passes
//! `spirv-val` (every 25th case in CI, see `spirv_every`), and whose CPU field is
//! finite everywhere we look. A new seed each CI run (printed in its log; `tests/lib.rs`
//! `fuzz_seed`), a fixed one locally.

use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};
use sdfc_compiler::emit::{self, Output, Target};
use sdfc_compiler::lower::{Entry, tracer::Options};
use sdfc_tests::scenes::scene;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Scenes generated; the total is stated in the issue notes.
const CASES: u32 = 20_000;

/// Every how many scenes `spirv-val` is run: 25 in CI (a call costs ~8 ms, the whole run 20 000
/// scenes), `SDFC_FUZZ_SPIRV_EVERY=1` for runs by hand that check every module.
fn spirv_every() -> usize {
    sdfc_tests::env_number("SDFC_FUZZ_SPIRV_EVERY")
        .filter(|&n| n > 0)
        .unwrap_or(25)
}

static VALID: AtomicUsize = AtomicUsize::new(0);
static TOTAL: AtomicUsize = AtomicUsize::new(0);
static SPIRV: AtomicUsize = AtomicUsize::new(0);

fn check_scene(source: &str, index: usize) {
    TOTAL.fetch_add(1, Ordering::Relaxed);
    let checked = sdfc_compiler::check::compile(source);
    let Some(scene) = checked.scene else {
        return;
    };
    VALID.fetch_add(1, Ordering::Relaxed);
    let (module, info) = emit::module(&scene, Entry::Compute, &Options::from_scene(&scene))
        .unwrap_or_else(|e| panic!("invalid module for\n{source}\n{}", e.0));
    if index.is_multiple_of(spirv_every()) {
        let Output::Binary(words) =
            emit::write(&module, &info, Target::Spirv, Entry::Compute).expect("SPIR-V")
        else {
            unreachable!()
        };
        let f = std::env::temp_dir().join(format!("sdfc-fuzz-{}-{index}.spv", std::process::id()));
        sdfc_tests::write_spirv(&f, &words);
        if let Ok(out) = std::process::Command::new("spirv-val")
            .args(["--target-env", "vulkan1.1"])
            .arg(&f)
            .output()
        {
            assert!(
                out.status.success(),
                "spirv-val rejected\n{source}\n{}",
                String::from_utf8_lossy(&out.stderr)
            );
            SPIRV.fetch_add(1, Ordering::Relaxed);
        }
        let _ = std::fs::remove_file(f);
    }
    for p in [
        glam::DVec3::ZERO,
        glam::DVec3::new(0.3, -0.2, 0.1),
        glam::DVec3::new(1e6, -1e6, 1e6),
        glam::DVec3::new(-3.0, 2.0, 7.0),
        glam::DVec3::splat(1e-9),
    ] {
        let d = sdfc_compiler::reference::eval::distance(&scene, p);
        assert!(d.is_finite(), "field {d} at {p} for\n{source}");
    }
}

#[test]
fn random_valid_scenes_compile_validate_and_evaluate_finitely() {
    sdfc_tests::with_stack(|| {
        let config = Config {
            cases: sdfc_tests::fuzz_cases(CASES),
            failure_persistence: None,
            rng_seed: RngSeed::Fixed(sdfc_tests::fuzz_seed(0x5dfc_5ce9e)),
            ..Config::default()
        };
        let counter = AtomicUsize::new(0);
        proptest!(config, |(seed in any::<u64>())| {
            let i = counter.fetch_add(1, Ordering::Relaxed);
            check_scene(&scene(seed), i);
        });
        let (valid, total) = (VALID.load(Ordering::Relaxed), TOTAL.load(Ordering::Relaxed));
        println!(
            "{total} generated scenes: {valid} valid (all compiled and validated), {} through spirv-val",
            SPIRV.load(Ordering::Relaxed)
        );
        assert!(
            valid * 2 >= total,
            "the generator makes too few valid scenes: {valid} of {total}"
        );
    });
}
