//! Scene parameters on the GPU: one compiled module, its `Params` uniform set to other values
//! and times between frames, each frame against the f64 reference at those values.

use crate::common;

use crate::common::{compile, gpu, off_by, srgb8};
use sdfc::gpu::TILE;
use sdfc::gpu::{Layout, Source};
use sdfc_compiler::emit;
use sdfc_compiler::lower::params::bytes;
use sdfc_compiler::lower::{Entry, tracer::Options};
use sdfc_compiler::reference::pixel;
use sdfc_compiler::view::View;
use std::collections::HashMap;

/// Most 8-bit levels a channel may differ by (f32 against f64).
const LEVELS: i32 = 2;

/// A scene with every kind of parameter use: a radius (primitive argument), a vector offset
/// (`at`), a smooth union's radius, a turn by `time`, an angle parameter (about a coordinate
/// axis and about another), an axis parameter, a `mix` weight, an `implicit` body, a
/// material's colour and specular strength, a light's direction, colour and intensity, and a
/// colour computed from a parameter.
pub(crate) const SCENE: &str = "\
camera { eye (0, 2.5, -6)  target (0, 0.6, 0) }
param sun = (-0.4, 1, -0.5) in (-1, 0.5, -1)..(1, 1, 1)
param warmth = #ffffff
param power = 1 in 0.5..1.5
param tint = #c04030
param shine = 0.5 in 0..1
light { direction sun  shadow soft  color warmth  intensity power }
light point { position (2, 3, -2)  intensity 0.4  color (shine, 0.5, 0.5) }
material red { color tint  specular shine }
param r = 0.8 in 0.4..1.2
param lift = (0, 0.9, 0) in (-1, 0, -1)..(1, 2, 1)
param blend = 0.3 in 0..0.6
param tilt = 0deg in -45deg..45deg
param morph = 0 in 0..1
param wave = 0.1 in 0..0.3
param axis = (0, 1, 0.3) in (-1, 0.5, -1)..(1, 1, 1)
smooth_union(blend) {
  sphere(r) at lift : red
  box((2.4, 0.3, 0.6)) |> rotate(z, tilt) |> rotate(y, time * 40deg) at (0, 0.3, 0)
}
mix(morph) { sphere(0.5)  box(0.8) } |> rotate((1, 1, 0), tilt) |> rotate(axis, 25deg) at (-2, 0.5, 0)
implicit { length(x - 2, y - 0.5, z) - 0.5 + wave * sin(6 * x) }
plane(y, 0)
";

/// Renders `scene`'s compiled module once per setting, changing only the uniform between
/// frames (`Prepared::set_params`), and compares each frame with the CPU reference of the
/// scene at those values (`Scene::with_values`). Each setting must give a different picture.
#[test]
fn one_module_draws_every_setting_as_the_cpu_reference() {
    let gpu = gpu();
    let scene = compile(SCENE);
    let names: Vec<&str> = scene.params.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "sun", "warmth", "power", "tint", "shine", "r", "lift", "blend", "tilt", "morph",
            "wave", "axis", "time"
        ],
        "the uniform's fields"
    );
    let (module, _) = emit::module(&scene, Entry::Compute, &Options::from_scene(&scene))
        .unwrap_or_else(|e| panic!("{}", e.0));
    let view = View::new(&scene.camera, 96, 64);
    gpu.set_params(&bytes(&scene.params));
    let prepared = gpu
        .prepare(
            Source::Module(&module),
            Layout::Full { passes: false },
            &view,
            None,
            TILE,
        )
        .unwrap();
    let settings: [&[(&str, &[f64])]; 5] = [
        &[],
        &[
            ("r", &[1.15]),
            ("lift", &[0.6, 1.4, -0.3]),
            ("blend", &[0.55]),
            ("morph", &[0.8]),
        ],
        &[
            ("time", &[1.5]),
            ("tilt", &[0.6]),
            ("axis", &[0.8, 0.6, -0.9]),
        ],
        &[
            ("time", &[4.0]),
            ("wave", &[0.3]),
            ("r", &[0.45]),
            ("blend", &[0.0]),
        ],
        &[
            ("sun", &[0.9, 0.6, 0.2]),
            ("warmth", &[1.0, 0.7, 0.4]),
            ("power", &[1.4]),
            ("tint", &[0.2, 0.6, 0.9]),
            ("shine", &[0.05]),
        ],
    ];
    let mut frames: Vec<Vec<u32>> = Vec::new();
    for setting in settings {
        let values: HashMap<String, Vec<f64>> = setting
            .iter()
            .map(|(n, v)| (n.to_string(), v.to_vec()))
            .collect();
        // Valid values, as `render --param` checks them.
        assert!(
            sdfc_compiler::check::compile_with(SCENE, &values)
                .scene
                .is_some(),
            "{values:?} should be valid"
        );
        let here = scene.with_values(&values);
        prepared.set_params(&bytes(&here.params));
        prepared.run_tiles(|_, _| {}).unwrap();
        let got = prepared.frame(0.0).unwrap();
        let (mut within, mut worst) = (0, 0);
        for (i, &px) in got.color.iter().enumerate() {
            let (x, y) = (
                (i as u32 % view.width) as f64 + 0.5,
                (i as u32 / view.width) as f64 + 0.5,
            );
            let c = pixel::pixel(&here, &here.trace, &view, x, y);
            let d = off_by(px, srgb8(c));
            worst = worst.max(d);
            within += u32::from(d <= LEVELS);
        }
        let share = f64::from(within) / got.color.len() as f64;
        println!(
            "{values:?}: {:.2}% within {LEVELS} levels of the CPU (worst {worst})",
            share * 100.0
        );
        assert!(
            share >= 0.998,
            "{values:?}: only {:.2}% match",
            share * 100.0
        );
        frames.push(got.color);
    }
    for a in 0..frames.len() {
        for b in a + 1..frames.len() {
            let changed = frames[a]
                .iter()
                .zip(&frames[b])
                .filter(|(x, y)| off_by(**x, srgb8_of(**y)) > 8)
                .count();
            assert!(
                changed > 100,
                "settings {a} and {b} draw the same picture ({changed} pixels differ)"
            );
        }
    }
}

/// The 8-bit sRGB channels of a packed pixel, for `off_by`.
fn srgb8_of(px: u32) -> [i32; 3] {
    let b = px.to_le_bytes();
    [b[0].into(), b[1].into(), b[2].into()]
}

/// Parameter values are not compiled in: the module of the scene checked with other values
/// (`compile_with`, as `render --param` checks them) is the defaults' module, to the byte.
#[test]
fn values_do_not_change_the_module() {
    let text = |values: &[(&str, &[f64])]| {
        let values: HashMap<String, Vec<f64>> = values
            .iter()
            .map(|(n, v)| (n.to_string(), v.to_vec()))
            .collect();
        let scene = sdfc_compiler::check::compile_with(SCENE, &values)
            .scene
            .expect("valid values");
        let (m, info) = emit::module(&scene, Entry::Compute, &Options::from_scene(&scene)).unwrap();
        match emit::write(&m, &info, emit::Target::Wgsl, Entry::Compute).unwrap() {
            emit::Output::Text(t) => t,
            emit::Output::Binary(_) => unreachable!(),
        }
    };
    let defaults = text(&[]);
    let other = text(&[
        ("r", &[0.41]),
        ("tint", &[0.1, 0.2, 0.3]),
        ("time", &[7.0]),
        ("tilt", &[-0.7]),
        ("sun", &[0.2, 0.9, -0.9]),
    ]);
    assert!(defaults == other, "a value changed the compiled module");
}

/// `render --frames` is one render per frame at `time` = k/fps with the module compiled once:
/// frame k of the sequence is, to the byte, `render --time k/fps`; the frames differ (the
/// lamp's head nods with `time`), and the GIF has every frame.
#[test]
fn animation_frames_are_renders_at_their_times() {
    let dir = common::scratch("frames");
    let scene = common::root().join("examples/lamp.sdf");
    let scene = scene.to_str().unwrap();
    let run = |args: &[&str]| {
        let o = common::sdfc(args);
        assert_eq!(
            o.status.code(),
            Some(0),
            "{args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    };
    let pattern = dir.join("f_##.png");
    let common_args = [
        "--size",
        "64x48",
        "--samples",
        "1",
        "--param",
        "reach=50deg",
    ];
    let mut args = vec!["render", scene, "--frames", "0..3", "--fps", "2", "-o"];
    args.push(pattern.to_str().unwrap());
    args.extend(common_args);
    run(&args);
    let frames: Vec<Vec<u8>> = (0..3)
        .map(|k| std::fs::read(dir.join(format!("f_{k:02}.png"))).unwrap())
        .collect();
    let single = dir.join("single.png");
    let mut args = vec![
        "render",
        scene,
        "--time",
        "0.5",
        "-o",
        single.to_str().unwrap(),
    ];
    args.extend(common_args);
    run(&args);
    assert!(
        std::fs::read(&single).unwrap() == frames[1],
        "frame 1 is not the render at time 0.5"
    );
    assert!(
        frames[0] != frames[1] && frames[1] != frames[2],
        "time does not move the lamp"
    );
    let gif = dir.join("anim.gif");
    let mut args = vec![
        "render",
        scene,
        "--frames",
        "0..3",
        "-o",
        gif.to_str().unwrap(),
    ];
    args.extend(common_args);
    run(&args);
    use image::AnimationDecoder;
    let decoder = image::codecs::gif::GifDecoder::new(std::io::BufReader::new(
        std::fs::File::open(&gif).unwrap(),
    ))
    .unwrap();
    let decoded = decoder.into_frames().collect_frames().unwrap();
    assert_eq!(decoded.len(), 3);
    assert_eq!(decoded[0].buffer().dimensions(), (64, 48));
}

/// `render --frames` refuses a frame whose `time` leaves the range the scene declares for it
/// (λ and bounds hold only there), before rendering anything.
#[test]
fn frames_stay_in_the_range_of_time() {
    let dir = common::scratch("time-range");
    let scene = dir.join("spin.sdf");
    std::fs::write(
        &scene,
        "param time = 0 in 0..1\nbox(1) |> rotate(y, time * 90deg)\n",
    )
    .unwrap();
    let out = dir.join("a.gif");
    let o = common::sdfc(&[
        "render",
        scene.to_str().unwrap(),
        "--frames",
        "0..40",
        "--fps",
        "30",
        "--size",
        "16x16",
        "-o",
        out.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("frame 31 is at time 1.0333") && err.contains("outside the range 0..1"),
        "{err}"
    );
    assert!(!out.exists());
}

/// `--param` takes what the parameter's declared kind takes: an angle needs its unit (a bare
/// number was read as radians behind the user's back), any other kind takes none, and only a
/// colour takes `#rrggbb`; each refusal names the parameter and how to write it.
#[test]
fn param_units_follow_the_declared_kind() {
    let dir = common::scratch("param-units");
    let scene = common::write(&dir, "scene.sdf", SCENE);
    let out = dir.join("out.png");
    let run = |param: &str| {
        let args = [
            "render", &scene, "--size", "16x12", "-q", "--param", param, "-o",
        ];
        common::sdfc(&[&args[..], &[out.to_str().unwrap()]].concat())
    };
    for (param, said) in [
        (
            "tilt=0.5",
            "`tilt` is an angle: give its unit\nhelp: `tilt=0.5deg` or `tilt=0.5rad`",
        ),
        (
            "r=30deg",
            "`r` is a number, not an angle: write it without `deg` or `rad`",
        ),
        ("lift=0,1rad,0", "`lift` is a vector, not an angle"),
        (
            "r=#ff0000",
            "`r` is a number, not a colour: `#rrggbb` is for colours",
        ),
    ] {
        let o = run(param);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "--param {param}: {err}");
        assert!(err.contains(said), "--param {param}: {err}");
        assert!(!err.contains("panicked"), "{err}");
    }
    for param in [
        "tilt=0.5rad",
        "tilt=20deg",
        "tint=#ff8800",
        "tint=1,0.5,0",
        "r=1",
    ] {
        let o = run(param);
        assert_eq!(
            o.status.code(),
            Some(0),
            "--param {param}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
}
