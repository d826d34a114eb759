//! What commands write and say: `-o -` to standard output, anti-aliasing samples at the
//! output's size, one line on success (none with `-q`), `error:` first on every error, output
//! extensions checked, `--version`, shell completions (and the README's lines installing them)
//! and the man page, the material channel.

use crate::common::{root, scratch, sdfc};
use std::process::Command;

/// `-o -` is standard output, for text and (when it is not a terminal) binary alike: the
/// shader text or the PNG arrive on stdout and no file named `-` appears.
#[test]
fn a_dash_output_is_standard_output() {
    let dir = scratch("dash-output");
    let scene = root().join("examples/gem.sdf");
    let scene = scene.to_str().unwrap();
    let run = |args: &[&str]| {
        let o = Command::new(env!("CARGO_BIN_EXE_sdfc"))
            .args(args)
            .current_dir(&dir)
            .output()
            .unwrap();
        assert_eq!(
            o.status.code(),
            Some(0),
            "{args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        o.stdout
    };
    let wgsl = run(&["emit", scene, "--entry", "library", "-o", "-"]);
    assert!(String::from_utf8_lossy(&wgsl).contains("fn map("));
    let png = run(&["render", scene, "--size", "16x9", "-o", "-"]);
    assert!(png.starts_with(b"\x89PNG\r\n\x1a\n"), "not a PNG");
    assert!(!dir.join("-").exists(), "a file named `-` was written");
    let _ = std::fs::remove_dir_all(dir);
}

/// Anti-aliasing samples are accumulated at the output's size: 64 samples of a 2100-pixel-wide
/// strip work (an 8× larger image would pass the 16384-pixel side limit), and `--samples` is
/// refused with `.npy` depth.
#[test]
fn many_samples_do_not_make_a_larger_image() {
    let dir = scratch("many-samples");
    let scene = root().join("examples/gem.sdf");
    let scene = scene.to_str().unwrap();
    let out = dir.join("strip.png");
    let o = sdfc(&[
        "render",
        scene,
        "-o",
        out.to_str().unwrap(),
        "--size",
        "2100x8",
        "--samples",
        "64",
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let img = image::open(&out).unwrap();
    assert_eq!((img.width(), img.height()), (2100, 8));
    let npy = dir.join("d.npy");
    let o = sdfc(&[
        "render",
        scene,
        "-o",
        npy.to_str().unwrap(),
        "--size",
        "8x8",
        "--channel",
        "depth",
        "--samples",
        "4",
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("one sample per pixel"));
    assert!(!npy.exists());
    let _ = std::fs::remove_dir_all(dir);
}

/// The rough edges a new user met: one line on success (and none with `-q`), every error
/// starting with `error:`, an output extension that does not match what is written refused
/// (naming the right ones) before anything is written.
#[test]
fn success_is_one_line_and_wrong_extensions_are_refused() {
    let dir = scratch("success-line");
    let scene = root().join("examples/gem.sdf");
    let scene = scene.to_str().unwrap();
    let png = dir.join("gem.png");
    let png = png.to_str().unwrap();
    let o = sdfc(&["render", scene, "-o", png, "--size", "16x9"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.starts_with(&format!("wrote {png} — 16×9, 4 samples per pixel, ")),
        "{err}"
    );
    assert!(err.contains("(vulkan)") || err.contains("(gl)"), "{err}");
    let o = sdfc(&["render", scene, "-o", png, "--size", "16x9", "-q"]);
    assert_eq!((o.status.code(), o.stderr.len()), (Some(0), 0));
    let wgsl = dir.join("gem.wgsl");
    let o = sdfc(&["emit", scene, "-o", wgsl.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.starts_with(&format!("wrote {} — WGSL, compute entry, ", wgsl.display())),
        "{err}"
    );
    let o = sdfc(&["--quiet", "emit", scene, "-o", wgsl.to_str().unwrap()]);
    assert_eq!((o.status.code(), o.stderr.len()), (Some(0), 0));
    // To standard output (`-o -`, or no `-o`) the line still goes to standard error, with the
    // bytes standard output received; `-q` keeps it quiet there too.
    for args in [&["-o", "-"][..], &[][..]] {
        let o = sdfc(&[&["emit", scene][..], args].concat());
        let err = String::from_utf8_lossy(&o.stderr);
        let said = format!(
            "wrote standard output — WGSL, compute entry, {} bytes",
            o.stdout.len()
        );
        assert_eq!(
            (o.status.code(), err.trim_end()),
            (Some(0), said.as_str()),
            "{args:?}"
        );
        assert!(String::from_utf8_lossy(&o.stdout).contains("fn map("));
    }
    let o = sdfc(&["emit", scene, "-o", "-", "-q"]);
    assert_eq!((o.status.code(), o.stderr.len()), (Some(0), 0));
    let refused: [(&[&str], &str); 3] = [
        (
            &["render", scene, "-o", "x.jpg"],
            "`.png`) and raw f32 depth (`.npy`), not `.jpg`",
        ),
        (&["render", scene, "-o", "x.stl"], "not `.stl`"),
        (
            &["emit", scene, "--target", "spirv", "-o", "x.wgsl"],
            "end in `.spv`, `.spirv`, not `.wgsl`",
        ),
    ];
    for (args, says) in refused {
        let mut a = args.to_vec();
        let out = dir.join(a[a.len() - 1]);
        let last = a.len() - 1;
        let out_s = out.to_str().unwrap().to_string();
        a[last] = &out_s;
        let o = sdfc(&a);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
        assert!(
            err.starts_with("error: ") && err.contains(says),
            "{args:?}: {err}"
        );
        assert!(!out.exists(), "{args:?} wrote a file");
    }
    // A message from the GPU layer (the device's storage limit) is an error too.
    let o = sdfc(&[
        "render",
        scene,
        "-o",
        png,
        "--size",
        "16384x16384",
        "--samples",
        "1",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.starts_with("error: "), "{err}");
    let _ = std::fs::remove_dir_all(dir);
}

/// `--version` names the version (and the commit when built from a git checkout); shell
/// completions for bash, zsh and fish and the man page are generated from the command line's
/// definition (bash's script parses with `bash -n`).
#[test]
fn version_completions_and_man_page() {
    let o = sdfc(&["--version"]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.starts_with(concat!("sdfc ", env!("CARGO_PKG_VERSION"))),
        "{out}"
    );
    let dir = scratch("completions");
    for shell in ["bash", "zsh", "fish"] {
        let o = sdfc(&["completions", shell]);
        let text = String::from_utf8_lossy(&o.stdout);
        assert_eq!(o.status.code(), Some(0), "{shell}");
        for word in ["render", "emit", "channel", "samples"] {
            assert!(text.contains(word), "{shell}: no `{word}`");
        }
        if shell == "bash" {
            let file = dir.join("sdfc.bash");
            std::fs::write(&file, text.as_bytes()).unwrap();
            let ok = Command::new("bash").arg("-n").arg(&file).status().unwrap();
            assert!(ok.success(), "the bash completions do not parse");
        }
    }
    let o = sdfc(&["man"]);
    let page = String::from_utf8_lossy(&o.stdout);
    assert!(
        page.contains(".TH sdfc") && page.contains("render"),
        "{page}"
    );
    // Every page sdfc(1) points to exists: `sdfc man --dir` writes one per subcommand.
    let pages = dir.join("man1");
    let o = sdfc(&["man", "--dir", pages.to_str().unwrap()]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let named: Vec<String> = page
        .split("sdfc\\-")
        .skip(1)
        .filter_map(|rest| rest.split_once("(1)").map(|(n, _)| format!("sdfc-{n}.1")))
        .collect();
    assert!(named.len() >= 6, "sdfc(1) names {named:?}");
    for file in &named {
        let text = std::fs::read_to_string(pages.join(file)).unwrap_or_default();
        let sub = file.trim_end_matches(".1");
        assert!(text.contains(&format!(".TH {sub}")), "{file}: {text:.200}");
    }
    let o = sdfc(&["man", "render"]);
    assert!(String::from_utf8_lossy(&o.stdout).contains(".TH sdfc-render"));
    let o = sdfc(&["man", "renderr"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("is no subcommand"));
    let _ = std::fs::remove_dir_all(dir);
}

/// The README's `render` synopsis is the one the command line's definition gives (`sdfc man
/// render --synopsis`): every flag there, in its order, none missing.
#[test]
fn the_readmes_render_synopsis_is_the_clis() {
    let o = sdfc(&["man", "render", "--synopsis"]);
    let synopsis = String::from_utf8_lossy(&o.stdout).to_string();
    assert!(synopsis.starts_with("sdfc render FILE"), "{synopsis}");
    for flag in ["--param", "--time", "--frames", "--watch", "--channel"] {
        assert!(synopsis.contains(flag), "{flag}: {synopsis}");
    }
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    assert!(
        readme.contains(&format!("```sh\n{synopsis}```")),
        "the README's render synopsis is stale: replace it with `sdfc man render --synopsis`:\n{synopsis}"
    );
}

/// The README's lines that install the bash completions work on a fresh machine (a home
/// without `~/.local/share/bash-completion`), run as written with `sdfc` on the path.
#[test]
fn the_readmes_completions_lines_work_in_a_fresh_home() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let lines: Vec<&str> = readme
        .lines()
        .filter(|l| l.contains("bash-completion/completions") || l.starts_with("sdfc man --dir"))
        .map(|l| l.split("   #").next().unwrap().trim())
        .collect();
    assert!(!lines.is_empty(), "the README names no completions file");
    let home = scratch("fresh-home");
    let _ = std::fs::remove_dir_all(&home);
    std::fs::create_dir_all(&home).unwrap();
    let bin = std::path::Path::new(env!("CARGO_BIN_EXE_sdfc"))
        .parent()
        .unwrap();
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let out = Command::new("bash")
        .args(["-euc", &lines.join("\n")])
        .env("HOME", &home)
        .env("PATH", path)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let script = home.join(".local/share/bash-completion/completions/sdfc");
    let text = std::fs::read_to_string(&script).unwrap();
    assert!(text.contains("_sdfc()"), "{}", &text[..text.len().min(200)]);
    let page = home.join(".local/share/man/man1/sdfc-render.1");
    assert!(
        page.exists(),
        "the README's man line wrote no {}",
        page.display()
    );
}

/// `--glsl-version 300es` writes GLSL ES 3.00 for the fragment entry and refuses the compute
/// entry (ES 3.00 has no compute shaders), saying which version has them.
#[test]
fn glsl_es_versions() {
    let scene = root().join("examples/gem.sdf");
    let scene = scene.to_str().unwrap();
    let o = sdfc(&[
        "emit",
        scene,
        "--target",
        "glsl",
        "--glsl-version",
        "300es",
        "--entry",
        "fragment",
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(o.stdout.starts_with(b"#version 300 es"));
    let o = sdfc(&["emit", scene, "--target", "glsl", "--glsl-version", "300es"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.starts_with("error: GLSL ES 3.00 has no compute shaders") && err.contains("310es"),
        "{err}"
    );
    let o = sdfc(&["emit", scene, "--target", "glsl", "--glsl-version", "310es"]);
    assert!(o.stdout.starts_with(b"#version 310 es"));
}

/// Diagnostics for editors and CI: `--message-format json` prints one JSON object per
/// diagnostic (file, severity, message, byte range, line and column, label, other places,
/// notes); the report is coloured with `--color always`, and plain when piped (the default).
#[test]
fn diagnostics_as_json_and_in_colour() {
    let dir = scratch("json");
    let file = dir.join("bad.sdf");
    std::fs::write(
        &file,
        "sphere(1)\nmaterial m { color #zz }\nsphere(1) : n\n",
    )
    .unwrap();
    let file = file.to_str().unwrap();
    let o = sdfc(&["check", file, "--message-format", "json"]);
    assert_eq!(o.status.code(), Some(1));
    let lines: Vec<serde_json::Value> = String::from_utf8_lossy(&o.stderr)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("{e}: {l}")))
        .collect();
    // Two errors and the summary object.
    assert_eq!(lines.len(), 3, "{lines:?}");
    assert_eq!(lines[2]["summary"]["errors"], 2, "{lines:?}");
    let colour = &lines[0];
    assert_eq!(colour["file"], file);
    assert_eq!(colour["severity"], "error");
    assert_eq!(colour["message"], "`#zz` is not a colour");
    let span = &colour["span"];
    assert_eq!(
        (span["line"].as_u64(), span["column"].as_u64()),
        (Some(2), Some(20))
    );
    assert_eq!(
        (span["start"].as_u64(), span["end"].as_u64()),
        (Some(29), Some(32))
    );
    assert!(
        lines[1]["message"].as_str().unwrap().contains("`n`"),
        "{}",
        lines[1]
    );
    let plain = sdfc(&["check", file]);
    assert!(
        !plain.stderr.contains(&0x1b),
        "escape codes in piped output"
    );
    let coloured = sdfc(&["check", file, "--color", "always"]);
    assert!(
        coloured.stderr.windows(2).any(|w| w == b"\x1b["),
        "no colour"
    );
    let _ = std::fs::remove_dir_all(dir);
}

/// A diagnostic inside an imported file names that file and its line, in the report and in
/// JSON, with the call in the importing file beside it.
#[test]
fn diagnostics_in_imported_files() {
    let dir = scratch("json-import");
    std::fs::create_dir_all(dir.join("lib")).unwrap();
    std::fs::write(
        dir.join("lib/parts.sdf"),
        "// parts\nfn shelf(w) = box((w, 0.1, 0.4)) at (0, heigth, 0)\n",
    )
    .unwrap();
    let file = dir.join("main.sdf");
    std::fs::write(&file, "import \"lib/parts.sdf\"\nshelf(2)\n").unwrap();
    let main = file.to_str().unwrap();
    let lib = dir.join("lib/parts.sdf").display().to_string();
    let o = sdfc(&["check", main, "--message-format", "json"]);
    assert_eq!(o.status.code(), Some(1));
    let text = String::from_utf8_lossy(&o.stderr);
    let d: serde_json::Value = serde_json::from_str(text.lines().next().unwrap()).unwrap();
    assert_eq!(d["file"], lib.as_str(), "{d}");
    assert_eq!(
        (d["span"]["line"].as_u64(), d["span"]["column"].as_u64()),
        (Some(2), Some(41))
    );
    assert_eq!(d["secondary"][0]["file"], main, "{d}");
    assert_eq!(d["secondary"][0]["span"]["line"].as_u64(), Some(2));
    let human = String::from_utf8_lossy(&sdfc(&["check", main]).stderr).to_string();
    assert!(human.contains(&format!("┌─ {lib}:2:41")), "{human}");
    assert!(human.contains(&format!("┌─ {main}:2:1")), "{human}");
}

/// The material channel tells a miss (black) from a hit in the default material (grey) and
/// from a declared material (a colour): a sphere in the default material and a box in `red`,
/// with the background around them (issue 30: misses were drawn in the default's grey).
#[test]
fn the_material_channel_tells_misses_from_the_default_material() {
    let dir = scratch("material-channel");
    let scene = dir.join("two.sdf");
    std::fs::write(
        &scene,
        "camera { eye (0, 0, -6) target (0, 0, 0) }\nmaterial red { color #f00 }\n\
         sphere(1) at (-1.5, 0, 0)\nbox(1.6) at (1.5, 0, 0) : red\n",
    )
    .unwrap();
    let png = dir.join("material.png");
    let out = sdfc(&[
        "render",
        scene.to_str().unwrap(),
        "-o",
        png.to_str().unwrap(),
        "--size",
        "64x32",
        "--channel",
        "material",
    ]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let img = image::open(&png).unwrap().to_rgba8();
    let at = |x: u32, y: u32| img.get_pixel(x, y).0;
    // The corner misses; the two shapes' centres are hit (which one is on the left depends
    // on the camera's handedness: either way, one grey and one coloured).
    let (miss, a, b) = (at(0, 0), at(16, 16), at(48, 16));
    let grey = [128, 128, 128, 255];
    assert_eq!(miss, [0, 0, 0, 255], "a miss");
    let (default, declared) = if a == grey { (a, b) } else { (b, a) };
    assert_eq!(default, grey, "the default material: {a:?} {b:?}");
    assert!(
        declared != miss && declared != grey,
        "the declared material: {declared:?}"
    );
}
