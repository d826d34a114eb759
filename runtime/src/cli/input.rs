//! Reading a scene file (or standard input) and reporting what the checker says of it; the
//! exit codes and standard output the commands share.

use super::Error;
use sdfc_compiler::check::{self, Checked};
use sdfc_compiler::lipschitz::{self, Effort};
use sdfc_compiler::source::Sources;
use std::path::Path;

/// The exit code of a command: 0, or 1 after printing its error (empty when the diagnostics
/// were printed already).
pub fn exit_code(result: Result<(), Error>) -> i32 {
    match result {
        Ok(()) => 0,
        Err(Error::Reported) => 1,
        Err(e) => {
            // Every error says so first (messages from the GPU layers do not).
            match e.to_string().as_str() {
                "" => {}
                e if e.starts_with("error") => say!("{e}"),
                e => say!("error: {e}"),
            }
            1
        }
    }
}

/// Reads and checks a scene, printing diagnostics; `None` (after printing) when it has errors.
/// (every `bake` at `bake_res`, when given: `--bake-res`).
pub fn load_scene(
    path: &Path,
    bake_res: Option<u32>,
) -> Option<(Sources, sdfc_compiler::scene::Scene)> {
    load_scene_with(
        path,
        &ParamArgs {
            bake_res,
            ..ParamArgs::default()
        },
    )
}

/// How a `--param` value was written: what its parameter's kind must accept.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Written {
    /// Numbers without a unit.
    Plain,
    /// Numbers with `deg` or `rad`.
    Angle,
    /// `#rrggbb`.
    Hex,
}

/// The `--param`s and `--time` of a command: the values (angles in radians) and how each was
/// written, which the parameter's declared kind must accept.
#[derive(Clone, Debug, Default)]
pub struct ParamArgs {
    /// Values by name.
    pub values: std::collections::HashMap<String, Vec<f64>>,
    /// How each `--param` was written, in the order given.
    pub written: Vec<(String, String, Written)>,
    /// `--bake-res`: the `res` of every `bake`.
    pub bake_res: Option<u32>,
}

impl ParamArgs {
    /// What the scene's defaults are compiled with: only `--bake-res` (not a parameter, so it
    /// applies to the host's module too).
    pub fn base(&self) -> std::collections::HashMap<String, Vec<f64>> {
        self.bake_res
            .map(|n| (check::BAKE_RES.to_string(), vec![f64::from(n)]))
            .into_iter()
            .collect()
    }

    /// The values and [`ParamArgs::base`] together.
    pub fn all(&self) -> std::collections::HashMap<String, Vec<f64>> {
        let mut all = self.values.clone();
        all.extend(self.base());
        all
    }
}

/// A `--param` written in a way its parameter's kind does not take: an angle needs its unit
/// (`30deg`, `0.5rad`: a bare number is not read as radians behind the user's back), any other
/// kind takes none, and only a colour takes `#rrggbb`.
fn unit_error(scene: &sdfc_compiler::scene::Scene, args: &ParamArgs) -> Option<String> {
    use sdfc_compiler::scene::ParamKind;
    args.written.iter().find_map(|(name, text, written)| {
        let p = scene.params.iter().find(|p| &p.name == name)?;
        let why = match (p.kind, written) {
            (ParamKind::Angle, Written::Plain) => format!(
                "`{name}` is an angle: give its unit\nhelp: `{name}={}deg` or `{name}={}rad`",
                text.trim(),
                text.trim()
            ),
            (ParamKind::Angle, Written::Angle) | (_, Written::Plain) => return None,
            (ParamKind::Color, Written::Hex) => return None,
            (kind, Written::Angle) => format!(
                "`{name}` is a {}, not an angle: write it without `deg` or `rad`",
                kind.name()
            ),
            (kind, Written::Hex) => {
                format!(
                    "`{name}` is a {}, not a colour: `#rrggbb` is for colours",
                    kind.name()
                )
            }
        };
        Some(format!("error: `--param {name}={}`: {why}", text.trim()))
    })
}

/// [`load_scene`] with `values` for parameters (`sdfc render --param`): they are checked as
/// the scene is at those values (kind, range, every argument's type), but the scene returned
/// is the defaults' — the module a host gets — whose `with_values` the caller applies to the
/// uniform only.
pub fn load_scene_with(
    path: &Path,
    args: &ParamArgs,
) -> Option<(Sources, sdfc_compiler::scene::Scene)> {
    let base = args.base();
    let values = &args.all();
    let (name, source) = match read_source(path) {
        Ok(x) => x,
        Err(e) => {
            say!("{e}");
            return None;
        }
    };
    let Checked {
        scene,
        mut diagnostics,
        sources,
    } = compile((path, &name), &source, &base);
    // The scene checked at the values asked for, once: for the annotations there and to
    // refuse values it cannot take.
    let at_values =
        (scene.is_some() && *values != base).then(|| compile((path, &name), &source, values));
    if let Some(scene) = &scene {
        // (`--bake-res` holds at every setting.)
        let at = |v: &std::collections::HashMap<String, Vec<f64>>| {
            let mut v = v.clone();
            v.extend(base.clone());
            match &at_values {
                Some(c) if v == *values => c.scene.clone(),
                _ => compile((path, &name), &source, &v).scene,
            }
        };
        diagnostics.extend(lipschitz::verify_everywhere(
            &at,
            scene,
            Effort::Fast,
            &args.values,
        ));
    }
    if let Some(e) = scene.as_ref().and_then(|s| unit_error(s, args))
        && !diagnostics.iter().any(|d| d.is_error())
    {
        say!("{e}");
        return None;
    }
    // The values must be valid: the diagnostics of the scene checked at them (its warnings
    // are the defaults' already).
    if let Some(at) = at_values.filter(|c| c.scene.is_none()) {
        diagnostics = at.diagnostics;
    }
    let scene = if diagnostics.iter().any(|d| d.is_error()) {
        None
    } else {
        scene
    };
    say_raw!("{}", super::messages::report(&diagnostics, &sources));
    let scene = scene?;
    let unknown = check::unknown_params(&scene, values);
    if let Some((bad, near)) = unknown.first() {
        let help = match near {
            Some(n) => format!("help: did you mean `{n}`?"),
            None if scene.params.is_empty() => "note: the scene declares no parameters".into(),
            None => format!(
                "note: its parameters are {}",
                scene
                    .params
                    .iter()
                    .map(|p| format!("`{}`", p.name))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        };
        say!("error: `--param {bad}`: `{name}` has no parameter `{bad}`\n{help}");
        return None;
    }
    Some((sources, scene))
}

/// The files on disk `path` imports (transitively, as far as they can be read and parsed;
/// the standard library is built in): what `--watch` and `sdfc view` follow besides it.
pub fn imported_files(path: &Path) -> Vec<std::path::PathBuf> {
    if path == Path::new("-") {
        return Vec::new();
    }
    let Ok((name, source)) = read_source(path) else {
        return Vec::new();
    };
    let loaded =
        sdfc_compiler::syntax::load_at(&name, path, &source, &sdfc_compiler::syntax::FsLoader);
    loaded
        .sources
        .files
        .iter()
        .skip(1)
        .filter(|f| !sdfc_compiler::syntax::STD.iter().any(|(n, _)| *n == f.name))
        .map(|f| std::path::PathBuf::from(&f.name))
        .chain(loaded.missing)
        .collect()
}

/// Checks the file at `path` (shown as `name`, text `source`) with its imports read from disk
/// beside `path` itself (not beside its lossy text: a Latin-1 folder name).
pub fn compile(
    (path, name): (&Path, &str),
    source: &str,
    values: &std::collections::HashMap<String, Vec<f64>>,
) -> Checked {
    check::compile_file_at(name, path, source, values, &sdfc_compiler::syntax::FsLoader)
}

/// The largest `--time` (or `--param time=`) in seconds, either side of 0: f32 resolves it to
/// 1/16 s there (`docs/language.md`).
pub const MAX_TIME: f64 = 1e6;

/// `--param NAME=VALUE`s and `--time T` as values for [`load_scene_with`]: a VALUE is a number
/// (an angle in radians, or with `deg`), `x,y,z` for a vector, or `#rrggbb` for a colour.
pub fn param_values(params: &[String], time: Option<f64>) -> Result<ParamArgs, Error> {
    let mut out = std::collections::HashMap::new();
    let mut written = Vec::new();
    for p in params {
        let bad = |why: &str| {
            format!(
                "error: `--param {p}`: {why}\nhelp: write NAME=VALUE: `r=1.5`, `spin=30deg`, `offset=0,1,0` or `tint=#ff8800`"
            )
        };
        let (name, value) = p.split_once('=').ok_or_else(|| bad("no `=`"))?;
        let name = name.trim();
        let value = value.trim();
        let how = if value.starts_with('#') {
            Written::Hex
        } else if value
            .split(',')
            .any(|x| x.trim().ends_with("deg") || x.trim().ends_with("rad"))
        {
            Written::Angle
        } else {
            Written::Plain
        };
        written.push((name.to_string(), value.to_string(), how));
        let parsed: Vec<f64> = if let Some(hex) = value.strip_prefix('#') {
            let digits: Option<Vec<u32>> = hex.chars().map(|c| c.to_digit(16)).collect();
            match (digits, hex.len()) {
                (Some(d), 6) => [0, 2, 4]
                    .map(|i| f64::from(d[i] * 16 + d[i + 1]) / 255.0)
                    .to_vec(),
                (Some(d), 3) => [0, 1, 2].map(|i| f64::from(d[i] * 17) / 255.0).to_vec(),
                _ => return Err(bad("not a colour `#rrggbb`").into()),
            }
        } else {
            value
                .split(',')
                .map(|x| {
                    let x = x.trim();
                    let (x, factor) = match x.strip_suffix("deg") {
                        Some(x) => (x, std::f64::consts::PI / 180.0),
                        None => (x.strip_suffix("rad").unwrap_or(x), 1.0),
                    };
                    x.trim()
                        .parse::<f64>()
                        .ok()
                        .filter(|v| v.is_finite())
                        .map(|v| v * factor)
                        .ok_or_else(|| bad(&format!("`{x}` is not a number")))
                })
                .collect::<Result<_, _>>()?
        };
        if name == sdfc_compiler::check::TIME && parsed.iter().any(|t| t.abs() > MAX_TIME) {
            return Err(bad(&format!(
                "give a time within ±{MAX_TIME:e} seconds (the shader computes in f32)"
            ))
            .into());
        }
        if out.insert(name.to_string(), parsed).is_some() {
            return Err(format!("error: `--param {name}` is given twice").into());
        }
    }
    if let Some(t) = time {
        if !t.is_finite() || t.abs() > MAX_TIME {
            return Err(format!("error: `--time {}`: give a time within ±{MAX_TIME:e} seconds\nnote: the shader computes in f32: at 1e6 s its time steps are 1/16 s, and at 1e39 it overflows (the shape vanished)", if t.abs() >= 1e6 { format!("{t:e}") } else { t.to_string() }).into());
        }
        if out
            .insert(sdfc_compiler::check::TIME.to_string(), vec![t])
            .is_some()
        {
            return Err("error: give the time with `--time` or `--param time=`, not both".into());
        }
    }
    Ok(ParamArgs {
        values: out,
        written,
        bake_res: None,
    })
}

/// Reads a scene file or standard input; the error is a message for the user. At most the
/// source limit and one byte more are read (`/dev/zero` is refused, not read until memory runs
/// out), and a UTF-8 byte-order mark, which Windows editors write, is dropped.
pub fn read_source(path: &Path) -> Result<(String, String), Error> {
    use std::io::Read;
    let limit = sdfc_compiler::syntax::MAX_SOURCE_BYTES;
    let (name, reader): (String, Box<dyn Read>) = if path == Path::new("-") {
        ("<stdin>".into(), Box::new(std::io::stdin()))
    } else {
        let name = path.display().to_string();
        let file =
            std::fs::File::open(path).map_err(|e| format!("error: cannot read `{name}`: {e}"))?;
        (name, Box::new(file))
    };
    let bytes = sdfc_compiler::syntax::read_limited(reader)
        .map_err(|e| format!("error: cannot read `{name}`: {e}"))?
        .ok_or_else(|| {
            format!("error: {name}:1:1: the file is larger than the source limit of {limit} bytes (4 MiB)")
        })?;
    let text = sdfc_compiler::syntax::decode(bytes)
        .map_err(|why| format!("error: cannot read `{name}`: {why}"))?;
    Ok((name, text))
}

/// Writes command output to standard output: a closed pipe (`sdfc check x.sdf | head -1`) ends
/// quietly, any other failure (a full device) is an error; `Err` holds the exit code.
pub fn print_out(text: &str) -> Result<(), i32> {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    match stdout
        .write_all(text.as_bytes())
        .and_then(|_| stdout.flush())
    {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Err(0),
        Err(e) => {
            say!("error: cannot write to standard output: {e}");
            Err(1)
        }
    }
}
