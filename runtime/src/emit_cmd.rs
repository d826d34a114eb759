//! `sdfc emit`: a scene to WGSL, SPIR-V, GLSL, MSL or HLSL, written whole or not at all.

use crate::cli::load_scene;
use sdfc_compiler::emit::{self, Output, Target};
use sdfc_compiler::lower::Entry;
use std::io::{IsTerminal, Write};
use std::path::Path;

/// `sdfc emit`'s options besides the target, entry and files.
pub struct Extras<'a> {
    /// Tracer overrides.
    pub tracer: &'a crate::cli::TracerArgs,
    /// `--prefix`.
    pub prefix: Option<&'a str>,
    /// `--entry shadertoy` (compiled as the library, written by `sdfc_compiler::shadertoy`).
    pub shadertoy: bool,
    /// `--params-binding`.
    pub params_binding: u32,
}

/// Runs `sdfc emit`; returns the exit code.
pub fn run(
    file: &Path,
    (target, entry): (Target, Entry),
    (output, manifest): (Option<&Path>, Option<&Path>),
    settings: &emit::Settings,
    extras: Extras,
) -> i32 {
    let Extras {
        tracer,
        prefix,
        shadertoy,
        params_binding,
    } = extras;
    if shadertoy && target != Target::Glsl {
        say!(
            "error: the Shadertoy entry is GLSL ES 3.00: `--entry shadertoy` takes `--target glsl` (or no `--target`)"
        );
        return 1;
    }
    if shadertoy && prefix.is_some() {
        say!(
            "error: `--prefix` is for the library; the Shadertoy shader is a whole Image tab with its own `mainImage`"
        );
        return 1;
    }
    if params_binding <= 8 && !matches!(entry, Entry::Library) {
        say!(
            "error: `--params-binding {params_binding}`: the entry's own resources use bindings 0 to 8; give 9 or more"
        );
        return 1;
    }
    let mut settings = *settings;
    if shadertoy {
        settings.glsl_version = emit::GlslVersion::Es300;
    }
    let settings = &settings;
    if let Some(path) = output
        && let Err(e) = check_extension(path, target)
    {
        say!("{e}");
        return 1;
    }
    if let Some(p) = prefix
        && !sdfc_compiler::manifest::valid_prefix(p)
    {
        say!(
            "error: `--prefix {p}` is not a name: it must start with a letter and go on with letters, digits or `_`"
        );
        return 1;
    }
    if let Some(m) = manifest
        && m.extension()
            .is_some_and(|e| !e.eq_ignore_ascii_case("json"))
    {
        say!(
            "error: `--manifest {}`: the manifest is JSON; give it a `.json` file",
            m.display()
        );
        return 1;
    }
    if target == Target::Glsl
        && !settings.glsl_version.has_compute()
        && matches!(entry, Entry::Compute | Entry::Trace)
    {
        say!(
            "error: GLSL ES 3.00 has no compute shaders: `--glsl-version 300es` is for `--entry fragment` or `--entry library`\nhelp: `--glsl-version 310es` (OpenGL ES 3.1) has them"
        );
        return 1;
    }
    let Some((sources, mut scene)) = load_scene(file) else {
        return 1;
    };
    let name = sources.main_name();
    let options = match tracer.settle(&mut scene) {
        Ok(mut o) => {
            o.private_params = shadertoy;
            o.params_binding = params_binding;
            o
        }
        Err(e) => {
            say!("{e}");
            return 1;
        }
    };
    if options.passes && entry != Entry::Compute {
        say!(
            "error: `--passes` is for the compute entry (the runtime's passes hand t from one to the next)"
        );
        return 1;
    }
    let compiled = emit::module(&scene, entry, &options).and_then(|(mut m, info)| {
        let Some(p) = prefix else {
            return Ok((m, info));
        };
        sdfc_compiler::manifest::prefix(&mut m, p);
        let info = emit::validate(&m)?;
        Ok((m, info))
    });
    let mut described = None;
    let result = compiled.and_then(|(m, info)| {
        if manifest.is_some() {
            let origin = sdfc_compiler::manifest::Origin {
                scene: name,
                target: target_name(target),
                entry,
                prefix,
            };
            described = Some(sdfc_compiler::manifest::manifest(&scene, &m, &origin));
        }
        emit::write_with(&m, &info, target, entry, settings).map(|out| match out {
            Output::Text(library) if shadertoy => {
                Output::Text(sdfc_compiler::shadertoy::wrap(&library, &scene))
            }
            other => other,
        })
    });
    let out = match result {
        Ok(o) => o,
        Err(e) => {
            say!("internal compiler error while compiling `{name}`: {}", e.0);
            say!(
                "note: this is a bug in sdfc, not in the scene; please report it with the scene file"
            );
            return 2;
        }
    };
    let bytes: Vec<u8> = match &out {
        Output::Text(s) => s.clone().into_bytes(),
        Output::Binary(words) => words.iter().flat_map(|w| w.to_le_bytes()).collect(),
    };
    let code = write_output(output, &bytes, matches!(out, Output::Binary(_)));
    if let (0, Some(path), Some(m)) = (code, manifest, described) {
        let text = serde_json::to_string_pretty(&m).expect("JSON") + "\n";
        if write_whole(path, text.as_bytes()) != 0 {
            return 1;
        }
    }
    if let (0, Some(path)) = (code, output.filter(|p| *p != Path::new("-"))) {
        let what = if shadertoy {
            "a Shadertoy Image shader (GLSL ES 3.00)".to_string()
        } else {
            describe(target, entry)
        };
        crate::cli::done(&format!(
            "wrote {} — {what}, {} bytes",
            path.display(),
            bytes.len()
        ));
    }
    code
}

/// `--glsl-version`.
#[derive(Clone, Copy, clap::ValueEnum)]
pub enum GlslVersionArg {
    /// Desktop GLSL 4.50 core.
    #[value(name = "450")]
    Core450,
    /// GLSL ES 3.10.
    #[value(name = "310es")]
    Es310,
    /// GLSL ES 3.00.
    #[value(name = "300es")]
    Es300,
}

impl From<GlslVersionArg> for emit::GlslVersion {
    fn from(v: GlslVersionArg) -> Self {
        match v {
            GlslVersionArg::Core450 => emit::GlslVersion::Core450,
            GlslVersionArg::Es310 => emit::GlslVersion::Es310,
            GlslVersionArg::Es300 => emit::GlslVersion::Es300,
        }
    }
}

/// The file extensions each target's output may have (an extension-less path, a device or a
/// pipe, takes any).
fn extensions(target: Target) -> &'static [&'static str] {
    match target {
        Target::Wgsl => &["wgsl"],
        Target::Spirv => &["spv", "spirv"],
        Target::Glsl => &["glsl", "comp", "frag", "vert"],
        Target::Msl => &["metal", "msl"],
        Target::Hlsl => &["hlsl", "fx"],
    }
}

/// Refuses an output file whose extension belongs to another language than the target's.
fn check_extension(path: &Path, target: Target) -> Result<(), String> {
    let Some(ext) = path.extension().and_then(|e| e.to_str()) else {
        return Ok(());
    };
    let allowed = extensions(target);
    if allowed.contains(&ext.to_ascii_lowercase().as_str()) {
        return Ok(());
    }
    let list: Vec<String> = allowed.iter().map(|e| format!("`.{e}`")).collect();
    Err(format!(
        "error: `{}`: `--target {}` writes {}; its files end in {}, not `.{ext}`",
        path.display(),
        target_name(target),
        describe_target(target),
        list.join(", ")
    ))
}

fn target_name(target: Target) -> &'static str {
    match target {
        Target::Wgsl => "wgsl",
        Target::Spirv => "spirv",
        Target::Glsl => "glsl",
        Target::Msl => "msl",
        Target::Hlsl => "hlsl",
    }
}

fn describe_target(target: Target) -> &'static str {
    match target {
        Target::Wgsl => "WGSL",
        Target::Spirv => "SPIR-V",
        Target::Glsl => "GLSL",
        Target::Msl => "Metal Shading Language",
        Target::Hlsl => "HLSL",
    }
}

/// "WGSL, compute entry".
fn describe(target: Target, entry: Entry) -> String {
    let entry = match entry {
        Entry::Compute => "compute entry",
        Entry::Fragment => "fragment entry",
        Entry::Library => "library",
        Entry::Trace => "trace-only entry",
        Entry::Rays | Entry::Field => "test entry",
    };
    format!("{}, {entry}", describe_target(target))
}

/// Writes a command's output: to standard output without a path or for `-` (binary output
/// refused on a terminal; a closed pipe is not an error), else the whole file; the exit code.
pub fn write_output(path: Option<&Path>, bytes: &[u8], binary: bool) -> i32 {
    match path.filter(|p| *p != Path::new("-")) {
        Some(path) => write_whole(path, bytes),
        None => {
            if binary && std::io::stdout().is_terminal() {
                say!("error: the output is binary; write it to a file with `-o FILE`");
                return 1;
            }
            let mut stdout = std::io::stdout().lock();
            match stdout.write_all(bytes).and_then(|_| stdout.flush()) {
                Ok(()) => 0,
                Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => 0,
                Err(e) => {
                    say!("error: cannot write to standard output: {e}");
                    1
                }
            }
        }
    }
}

/// Writes a whole file, printing the error; the exit code.
pub fn write_whole(path: &Path, bytes: &[u8]) -> i32 {
    match sdfc::files::write_file(path, bytes) {
        Ok(()) => 0,
        Err(e) => {
            say!("error: cannot write `{}`: {e}", path.display());
            1
        }
    }
}
