//! The Lipschitz promise over parameters' ranges: random scenes whose arguments are sometimes
//! ranged parameters, and fixed tight ones, sampled at the ranges' ends and inside, with the
//! scene checked at its defaults and set to those values (`Scene::with_values`).

use crate::lipschitz_sampler::{Tally, parametric_source, promised_nodes, sample_node};
use glam::DVec3;
use sdfc_compiler::reference::eval;
use sdfc_tests::Rng;
use std::collections::HashMap;

/// Scenes whose arguments are parameters (`param`, with ranges): λ, bounds and symmetries hold
/// for every value of the range, so the sampling test passes at the range's ends and at random
/// values inside: the scene as checked with its defaults, its parameters then set to those
/// values (`Scene::with_values`, what the shader does with the uniform).
#[test]
fn bounds_hold_over_parameter_ranges() {
    sdfc_tests::with_stack(|| {
        let scenes =
            sdfc_tests::env_number("SDFC_LIPSCHITZ_SCENES").map_or(PARAMETRIC, |n: usize| n / 4);
        let seed = sdfc_tests::fuzz_seed(0x9a4a_3e71);
        let mut tally = Tally::default();
        let (mut valid, mut with_params, mut settings) = (0, 0, 0);
        let mut r = Rng::new(seed);
        let fixed = FIXED_PARAMETRIC.iter().map(|s| s.to_string());
        let random: Vec<String> = (0..scenes).map(|_| parametric_source(r.bits())).collect();
        for (k, source) in fixed.chain(random).enumerate() {
            let Some(scene) = sdfc_compiler::check::compile(&source).scene else {
                assert!(k >= FIXED_PARAMETRIC.len(), "{source}\ndoes not check");
                continue;
            };
            valid += 1;
            let ranged: Vec<_> = scene.params.iter().filter(|p| p.range.is_some()).collect();
            if ranged.is_empty() {
                continue;
            }
            with_params += 1;
            // The low ends, the high ends, and two random points of the box of ranges.
            for k in 0..4 {
                let values: HashMap<String, Vec<f64>> = ranged
                    .iter()
                    .map(|p| {
                        let (lo, hi) = p.range.expect("ranged");
                        let v = match k {
                            0 => lo.x,
                            1 => hi.x,
                            _ => lo.x + (hi.x - lo.x) * r.unit(),
                        };
                        (p.name.clone(), vec![v.clamp(lo.x, hi.x)])
                    })
                    .collect();
                // The values are valid ones (checked as `render --param` checks them)...
                let at = sdfc_compiler::check::compile_with(&source, &values);
                assert!(
                    at.scene.is_some(),
                    "{source}\nfails to check at {values:?}: {:?}",
                    at.diagnostics
                );
                // ...and the field there is the default scene's, as the shader computes it:
                // λ, bounds and `repeat`'s copies from the check, the arguments from the values.
                let here = scene.with_values(&values);
                settings += 1;
                let note = format!("{source}\n(at {values:?})");
                for id in promised_nodes(&here) {
                    sample_node(&here, id, &mut r, &note, &mut tally);
                }
            }
        }
        println!(
            "{valid} of {scenes} parametric scenes valid, {with_params} with parameters, checked at {settings} settings; {} points sampled",
            tally.points
        );
        tally.assert_no_violations(3);
        assert!(
            with_params * 10 >= scenes * 4,
            "too few scenes with parameters: {with_params} of {scenes}"
        );
        assert!(tally.points >= 20_000, "only {} points", tally.points);
    });
}

/// Scenes whose bounds depend on their parameters, tightly: `mix`'s λ is (1 − w)·3 + w·1
/// (the implicit's gradient is 3 everywhere), largest at w = 0, the default being 1; a
/// `repeat` must look at enough copies for the largest radius and offset; a turned bar.
const FIXED_PARAMETRIC: &[&str] = &[
    "param w = 1 in 0..1\nmix(w) { implicit { 3 * (length(x, y, z) - 1) }  sphere(1) }",
    "param r = 0.3 in 0.2..1.4\nparam d = 0 in -1..1\nrepeat(spacing = (3, 3, 3)) { sphere(r) at (d, 0, 0) }",
    "param a = 0deg in 0deg..90deg\nrepeat(spacing = (3, 0, 0)) { box((2.4, 0.3, 0.3)) |> rotate(z, a) }",
];

/// `repeat` looks at the copies the bound of its shape over the whole range calls for: with
/// the shape's radius and offset at other values than the defaults, the repeated field is
/// still the union of every copy (an exact field, so they agree to rounding).
#[test]
fn repeat_of_a_parametric_shape_is_the_union_of_its_copies() {
    let source = "param r = 0.2 in 0.2..0.95\nparam d = 0 in -1.5..1.5\nrepeat(spacing = (2, 0, 0)) { sphere(r) at (d, 0, 0) }";
    let scene = sdfc_compiler::check::compile(source).scene.expect("checks");
    let mut rng = Rng::new(7);
    let mut compared = 0;
    for (r, d) in [
        (0.95, 1.5),
        (0.95, -1.5),
        (0.6, 1.2),
        (0.2, -1.5),
        (0.9, 0.9),
    ] {
        let values = HashMap::from([("r".to_string(), vec![r]), ("d".to_string(), vec![d])]);
        let here = scene.with_values(&values);
        for _ in 0..2000 {
            let p = DVec3::new(
                rng.range(-4.0, 4.0),
                rng.range(-1.5, 1.5),
                rng.range(-1.5, 1.5),
            );
            let union = (-6..=6)
                .map(|k| (p - DVec3::new(f64::from(k) * 2.0 + d, 0.0, 0.0)).length() - r)
                .fold(f64::INFINITY, f64::min);
            let field = eval::distance(&here, p);
            assert!(
                (field - union).abs() < 1e-9,
                "at r = {r}, d = {d}, p = {p}: repeat gives {field}, the copies {union}"
            );
            compared += 1;
        }
    }
    assert_eq!(compared, 10_000);
}

/// A turn whose range holds only whole eighth turns at its evenly spaced samples (0°..720° in
/// 17 samples is every 45°, 0°..1440° every 90°) is not symmetric across the cell at other
/// values: `repeat` must not take the own cell's copy alone. At 30° and 45° the repeated square
/// bar is the union of its copies written out.
#[test]
fn repeat_of_a_ranged_turn_is_the_union_of_its_copies() {
    let mut rng = Rng::new(9);
    for top in ["720deg", "1440deg"] {
        let source = format!(
            "param a = 0deg in 0deg..{top}\nrepeat(spacing = (3, 0, 0), count = (7, 1, 1)) {{ box((1.2, 1.2, 0.3)) |> rotate(z, a) }}"
        );
        let scene = sdfc_compiler::check::compile(&source)
            .scene
            .expect("checks");
        for deg in [30.0_f64, 45.0] {
            let values = HashMap::from([("a".to_string(), vec![deg.to_radians()])]);
            let here = scene.with_values(&values);
            let copies: Vec<String> = (-3..=3)
                .map(|k| {
                    format!(
                        "box((1.2, 1.2, 0.3)) |> rotate(z, {deg}deg) at ({}, 0, 0)",
                        3 * k
                    )
                })
                .collect();
            let union = sdfc_tests::scene("union", &format!("union {{ {} }}", copies.join("\n")));
            for _ in 0..2000 {
                let p = DVec3::new(
                    rng.range(-9.0, 9.0),
                    rng.range(-1.5, 1.5),
                    rng.range(-1.0, 1.0),
                );
                let (a, b) = (eval::distance(&here, p), eval::distance(&union, p));
                assert!(
                    (a - b).abs() < 1e-9,
                    "{top}, {deg}° at {p}: repeat {a}, the copies {b}"
                );
            }
        }
    }
}

/// Parametric scenes per CI run.
const PARAMETRIC: usize = 400;
