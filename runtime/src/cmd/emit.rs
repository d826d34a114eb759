//! `sdfc emit`: a scene to WGSL, SPIR-V, GLSL, MSL or HLSL, written whole or not at all.

use super::common::write_output;
use crate::cli::input::load_scene;
use crate::cli::values::{EntryArg, TargetArg};
use crate::cli::{EmitArgs, Error};
use crate::view::watch::watching;
use sdfc_compiler::emit::{self, Output, Target};
use sdfc_compiler::lower::Entry;
use std::path::Path;

/// What `sdfc emit` makes of its flags: the target, entry and writer's settings.
struct Plan {
    target: Target,
    entry: Entry,
    settings: emit::Settings,
    /// `--entry shadertoy` (compiled as the library, written by `sdfc_compiler::shadertoy`).
    shadertoy: bool,
}

/// Runs `sdfc emit` (again on every save with `--watch`); returns the exit code.
pub fn run(args: &EmitArgs) -> i32 {
    let shadertoy = matches!(args.entry, EntryArg::Shadertoy);
    let target = match (args.target, shadertoy) {
        (Some(t), _) => t,
        (None, true) => TargetArg::Glsl,
        (None, false) => TargetArg::Wgsl,
    };
    let mut settings = emit::Settings {
        spirv_version: args.spirv_version.pair(),
        glsl_version: args.glsl_version.into(),
    };
    if shadertoy {
        settings.glsl_version = emit::GlslVersion::Es300;
    }
    let plan = Plan {
        target: target.into(),
        entry: args.entry.into(),
        settings,
        shadertoy,
    };
    watching(&args.file, args.watch, || once(args, &plan))
}

/// One run of `sdfc emit`; the exit code.
fn once(args: &EmitArgs, plan: &Plan) -> i32 {
    if let Err(e) = check_flags(args, plan) {
        say!("{e}");
        return 1;
    }
    let Some((sources, mut scene)) = load_scene(&args.file, args.bake.bake_res) else {
        return 1;
    };
    let name = sources.main_name();
    let options = match args.tracer.settle_emitted(&mut scene) {
        Ok(mut o) => {
            o.private_params = plan.shadertoy;
            o.params_binding = args.params_binding;
            o
        }
        Err(e) => {
            say!("{e}");
            return 1;
        }
    };
    if options.passes && plan.entry != Entry::Compute {
        say!(
            "error: `--passes` is for the compute entry (the runtime's passes hand t from one to the next)"
        );
        return 1;
    }
    let data = match data_form(plan, &scene, &options) {
        Ok(d) => d,
        Err(e) => {
            say!("{e}");
            return 1;
        }
    };
    let mut sides = match volume_paths(args, plan, &scene) {
        Ok(v) => v,
        Err(e) => {
            say!("{e}");
            return 1;
        }
    };
    let volumes = sides.len();
    match data.as_ref().map(|d| data_paths(args, d)).transpose() {
        Ok(d) => sides.extend(d.into_iter().flatten()),
        Err(e) => {
            say!("{e}");
            return 1;
        }
    }
    let files: Vec<String> = sides
        .iter()
        .map(|(p, _)| {
            p.file_name()
                .map_or(String::new(), |n| n.to_string_lossy().into())
        })
        .collect();
    let (volume_files, data_files) = files.split_at(volumes);
    let data_files = data
        .as_ref()
        .map(|data| sdfc_compiler::manifest::DataFiles {
            data,
            files: data_files,
        });
    let given = (name, volume_files, data_files);
    let (out, manifest) = match compile(args, plan, &scene, &options, given) {
        Ok(o) => o,
        Err(e) => {
            say!("internal compiler error while compiling `{name}`: {}", e.0);
            say!(
                "note: this is a bug in sdfc, not in the scene; please report it with the scene file"
            );
            return 2;
        }
    };
    write(args, plan, &out, manifest, &sides)
}

/// The data form's buffers, made at the parameters' defaults, where the scene is compiled to
/// the data form (`--form data`); an error where the target cannot bind storage buffers.
fn data_form(
    plan: &Plan,
    scene: &sdfc_compiler::scene::Scene,
    options: &sdfc_compiler::lower::tracer::Options,
) -> Result<Option<sdfc_compiler::tape::data::Data>, Error> {
    if options.form != sdfc_compiler::lower::tracer::Form::Data {
        return Ok(None);
    }
    if plan.shadertoy {
        return Err("error: `--form data` reads the scene's parts from storage buffers, and a Shadertoy tab has none of your own\nhelp: `--form inline` (the default) writes every part into the code".into());
    }
    if plan.target == Target::Glsl && !plan.settings.glsl_version.has_compute() {
        return Err("error: `--form data` reads the scene's parts from storage buffers, which GLSL ES 3.00 (WebGL2) does not have\nhelp: `--form inline` (the default), or `--glsl-version 310es` or `450`".into());
    }
    crate::cli::tape_data(scene, scene, options.cells).map(Some)
}

/// Where the data form's buffers are written (beside the shader, or beside the manifest when
/// the shader goes to standard output: `NAME.nodes.u32`, `NAME.code.u32`, `NAME.ranges.u32`)
/// with their bytes.
fn data_paths(
    args: &EmitArgs,
    data: &sdfc_compiler::tape::data::Data,
) -> Result<Vec<(std::path::PathBuf, Vec<u8>)>, Error> {
    let Some(beside) = beside(args) else {
        return Err("error: `--form data` writes the scene's parts into files beside the shader: give the shader a file with `-o FILE` (or a manifest with `--manifest FILE`)".into());
    };
    let stem = stem(&beside);
    let names = sdfc_compiler::tape::data::BUFFERS.map(|(n, _)| n);
    Ok(names
        .iter()
        .zip(data.buffers())
        .map(|(n, bytes)| {
            let name = sdfc_compiler::tape::data::file_name(&stem, n);
            (beside.with_file_name(name), bytes)
        })
        .collect())
}

/// The file the files a shader reads are written beside: the shader's, else the manifest's.
fn beside(args: &EmitArgs) -> Option<std::path::PathBuf> {
    let file = |p: Option<&Path>| p.filter(|p| *p != Path::new("-")).map(Path::to_path_buf);
    file(args.output.as_deref()).or_else(|| file(args.manifest.as_deref()))
}

/// A file's name without its extension (`scene` if it has none).
fn stem(path: &Path) -> String {
    path.file_stem()
        .map_or("scene".into(), |s| s.to_string_lossy().into_owned())
}

/// Where each baked volume of the scene is written (beside the shader, or beside the manifest
/// when the shader goes to standard output: `NAME.volumeI.r32f`) with its bytes; an error
/// when there is no file to write them beside, or the target cannot read them.
fn volume_paths(
    args: &EmitArgs,
    plan: &Plan,
    scene: &sdfc_compiler::scene::Scene,
) -> Result<Vec<(std::path::PathBuf, Vec<u8>)>, Error> {
    let volumes = scene.volumes();
    if volumes.is_empty() {
        return Ok(Vec::new());
    }
    if plan.shadertoy {
        return Err("error: this scene bakes a part (`bake`) into a 3D texture, and a Shadertoy tab has no input for one of your own\nhelp: emit WGSL or GLSL for a host that binds the texture (docs/bake.md)".into());
    }
    let Some(beside) = beside(args) else {
        return Err("error: this scene bakes a part (`bake`), and its volume is written beside the shader: give the shader a file with `-o FILE` (or a manifest with `--manifest FILE`)".into());
    };
    let stem = stem(&beside);
    Ok(volumes
        .iter()
        .enumerate()
        .map(|(i, v)| {
            let path = beside.with_file_name(sdfc_compiler::bake::file::raw_name(&stem, i));
            (path, sdfc_compiler::bake::file::raw(v))
        })
        .collect())
}

/// Refuses flags that do not go together, or files whose names say another format.
fn check_flags(args: &EmitArgs, plan: &Plan) -> Result<(), Error> {
    let (target, entry, shadertoy) = (plan.target, plan.entry, plan.shadertoy);
    let prefix = args.prefix.as_deref();
    if shadertoy && target != Target::Glsl {
        return Err("error: the Shadertoy entry is GLSL ES 3.00: `--entry shadertoy` takes `--target glsl` (or no `--target`)".into());
    }
    if shadertoy && prefix.is_some() {
        return Err("error: `--prefix` is for the library; the Shadertoy shader is a whole Image tab with its own `mainImage`".into());
    }
    let binding = args.params_binding;
    if binding <= 8 && !matches!(entry, Entry::Library) {
        return Err(format!("error: `--params-binding {binding}`: the entry's own resources use bindings 0 to 8; give 9 or more").into());
    }
    if let Some(path) = args.output.as_deref() {
        check_extension(path, target)?;
    }
    if let Some(p) = prefix
        && !sdfc_compiler::manifest::valid_prefix(p)
    {
        return Err(format!("error: `--prefix {p}` is not a name: it must start with a letter and go on with letters, digits or `_`").into());
    }
    if let Some(m) = args.manifest.as_deref()
        && m.extension()
            .is_some_and(|e| !e.eq_ignore_ascii_case("json"))
    {
        return Err(format!(
            "error: `--manifest {}`: the manifest is JSON; give it a `.json` file",
            m.display()
        )
        .into());
    }
    if target == Target::Glsl
        && !plan.settings.glsl_version.has_compute()
        && matches!(entry, Entry::Compute | Entry::Trace)
    {
        return Err("error: GLSL ES 3.00 has no compute shaders: `--glsl-version 300es` is for `--entry fragment` or `--entry library`\nhelp: `--glsl-version 310es` (OpenGL ES 3.1) has them".into());
    }
    Ok(())
}

/// The scene's module in the target's language (and its manifest, if asked for).
fn compile(
    args: &EmitArgs,
    plan: &Plan,
    scene: &sdfc_compiler::scene::Scene,
    options: &sdfc_compiler::lower::tracer::Options,
    (name, volume_files, data): (&str, &[String], Option<sdfc_compiler::manifest::DataFiles>),
) -> Result<(Output, Option<serde_json::Value>), emit::InternalError> {
    let (target, entry) = (plan.target, plan.entry);
    let prefix = args.prefix.as_deref();
    let (m, info) = emit::module(scene, entry, options).and_then(|(mut m, info)| {
        let Some(p) = prefix else {
            return Ok((m, info));
        };
        sdfc_compiler::manifest::prefix(&mut m, p);
        let info = emit::validate(&m)?;
        Ok((m, info))
    })?;
    let (out, reflection) = emit::write_reflected(&m, &info, target, entry, &plan.settings)?;
    let described = args.manifest.is_some().then(|| {
        let origin = sdfc_compiler::manifest::Origin {
            volume_files,
            data,
            scene: name,
            target: target.name(),
            entry,
            prefix,
            written: Some((&out, &reflection)),
        };
        sdfc_compiler::manifest::manifest(scene, &m, &origin)
    });
    let out = match out {
        Output::Text(library) if plan.shadertoy => {
            Output::Text(sdfc_compiler::shadertoy::wrap(&library, scene))
        }
        other => other,
    };
    Ok((out, described))
}

/// Writes the output (and the manifest) and says so; the exit code.
fn write(
    args: &EmitArgs,
    plan: &Plan,
    out: &Output,
    manifest: Option<serde_json::Value>,
    volumes: &[(std::path::PathBuf, Vec<u8>)],
) -> i32 {
    let bytes: Vec<u8> = match out {
        Output::Text(s) => s.clone().into_bytes(),
        Output::Binary(words) => words.iter().flat_map(|w| w.to_le_bytes()).collect(),
    };
    let output = args.output.as_deref();
    // Both outputs or neither: every folder is checked before anything is written.
    let stdout = |p: Option<&Path>| p.is_none_or(|p| p == Path::new("-"));
    if args.manifest.is_some() && stdout(output) && stdout(args.manifest.as_deref()) {
        say!(
            "error: the shader and `--manifest -` would both go to standard output: give one of them a file"
        );
        return 1;
    }
    let volume_files = volumes.iter().map(|(p, _)| p.as_path());
    for path in [output, args.manifest.as_deref()]
        .into_iter()
        .flatten()
        .chain(volume_files)
    {
        if let Err(e) = super::common::writable(path) {
            say!("{e}");
            return 1;
        }
    }
    // Standard output first (the write that cannot be foreseen to fail: a full disk, a closed
    // pipe), so that a failure there leaves no file written.
    let shader = (output, bytes.as_slice(), matches!(out, Output::Binary(_)));
    let text = manifest.map(|m| serde_json::to_string_pretty(&m).expect("JSON") + "\n");
    let described = args
        .manifest
        .as_deref()
        .zip(text.as_deref())
        .map(|(p, t)| (Some(p), t.as_bytes(), false));
    let baked = volumes
        .iter()
        .map(|(p, b)| (Some(p.as_path()), b.as_slice(), true));
    // The volumes first (the largest, the likeliest to meet a full disk), so that a failure
    // there leaves an earlier shader and manifest as they were.
    let mut writes: Vec<_> = baked
        .chain(described)
        .chain(std::iter::once(shader))
        .collect();
    writes.sort_by_key(|(p, _, _)| !stdout(*p));
    let mut code = 0;
    // Files this run created, removed again if a later write fails: nothing partial.
    let mut created = Vec::new();
    for (path, bytes, binary) in writes {
        let new = path.filter(|p| !stdout(Some(p)) && !p.exists());
        code = write_output(path, bytes, binary);
        if code != 0 {
            created.iter().for_each(|p| _ = std::fs::remove_file(p));
            return code;
        }
        created.extend(new);
    }
    if code == 0 {
        let what = if plan.shadertoy {
            "a Shadertoy Image shader (GLSL ES 3.00)".to_string()
        } else {
            describe(plan.target, plan.entry)
        };
        // Standard output carries the code; the line goes to standard error, as every
        // command's does.
        let to = match output.filter(|p| *p != Path::new("-")) {
            Some(path) => path.display().to_string(),
            None => "standard output".to_string(),
        };
        crate::cli::messages::done(&format!("wrote {to} — {what}, {} bytes", bytes.len()));
    }
    code
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
fn check_extension(path: &Path, target: Target) -> Result<(), Error> {
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
        target.name(),
        describe_target(target),
        list.join(", ")
    )
    .into())
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
