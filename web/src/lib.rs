//! sdfc's compiler in the browser: `compile(request)` takes a scene's source and returns the
//! shader, its manifest and the diagnostics as `sdfc emit` and `sdfc check --message-format json`
//! give them, as JSON, through plain WebAssembly exports (`sdfc_alloc`, `sdfc_compile`,
//! `sdfc_free`, `sdfc_volume`, `sdfc_data`, `sdfc_seed` and the memory) that `web/sdfc.mjs`
//! wraps; a scene of many parts compiles to the data form for WebGPU, its buffers made at the
//! page's values by `sdfc_data`, or pruned by the page's device from `sdfc_seed`. No
//! wasm-bindgen: a string in and a string out need no generated glue, and the build needs no
//! tool beyond cargo (our choice; issue 36 suggested wasm-bindgen).
//!
//! Imports resolve against the built-in standard library only (`std/…`): the page has no files.

use sdfc_compiler::bake::Volume;
use sdfc_compiler::check::{self, Checked};
use sdfc_compiler::diag::{self, Diagnostic};
use sdfc_compiler::emit::{self, GlslVersion, Output, Target};
use sdfc_compiler::lipschitz::{self, Effort, Values};
use sdfc_compiler::lower::{Entry, tracer::Options};
use sdfc_compiler::scene::{Scene, Trace};
use sdfc_compiler::syntax::NoFiles;
use sdfc_compiler::tape::data::Layout;
use serde_json::{Value, json};
use std::sync::Arc;

/// What the page asks for: `{"source", "name", "target": "wgsl"|"glsl", "entry":
/// "fragment"|"compute"|"library", "tracer": {"name", "settings": {"steps": "64", …}}}` (GLSL
/// is ES 3.00 for WebGL2: fragment or library only; the tracer overrides the scene's as
/// `sdfc emit --tracer NAME --steps 64` does, values as those flags take them). Missing fields
/// take those defaults: `scene.sdf`, WGSL, the fragment entry, the scene's tracer, `"form":
/// "auto"` (a scene of many parts as data for WGSL; `"inline"` keeps every part in the code);
/// `"annotations": "later"` skips sampling the `@lipschitz` claims (see [`checked`]). The answer
/// also says the tracer used (`"tracer": {"name", "settings": [[name, value], …]}`) and every
/// tracer's parameters (`"tracers"`), for the page's panel.
pub fn compile(request: &str) -> String {
    let request: Value = serde_json::from_str(request).unwrap_or(Value::Null);
    let text = |key: &str, default: &'static str| -> String {
        request
            .get(key)
            .and_then(Value::as_str)
            .unwrap_or(default)
            .to_string()
    };
    // A byte-order mark dropped, as the CLI drops it from a file.
    let source = sdfc_compiler::syntax::decode(text("source", "").into_bytes()).unwrap_or_default();
    let name = text("name", "scene.sdf");
    let wanted = (text("target", "wgsl"), text("entry", "fragment"));
    let (target, entry) = match choose(&wanted) {
        Ok(te) => te,
        Err(why) => return json!({ "ok": false, "error": why }).to_string(),
    };
    // `"annotations": "later"`: the `@lipschitz` claims are not sampled now (their check only
    // ever warns, and the shader does not depend on it); the answer says `"pending": true`
    // where a check with `"now"` (the default) would sample some.
    let later = text("annotations", "now") == "later";
    let (checked, diagnostics, pending) = checked(&name, &source, later);
    let mut response = json!({
        "ok": false,
        "diagnostics": diagnostics
            .iter()
            .map(|d| diag::json::one(d, &checked.sources))
            .collect::<Vec<_>>(),
        "summary": diag::json::summary(&diag::shown(&diagnostics).1)["summary"],
        "pending": pending,
    });
    response["tracers"] = tracers();
    let Some(mut scene) = checked
        .scene
        .filter(|_| !diagnostics.iter().any(Diagnostic::is_error))
    else {
        return response.to_string();
    };
    match overridden(scene.trace, request.get("tracer")) {
        Ok(trace) => scene.trace = trace,
        Err(why) => {
            response["error"] = json!(why);
            return response.to_string();
        }
    }
    let (method, settings) = check::tracer::settings(&scene.trace);
    response["tracer"] = json!({ "name": method, "settings": settings });
    // `"form": "inline"` (the downloads: what `sdfc emit` writes) keeps every part in the code.
    let inline = text("form", "auto") == "inline";
    let made = emitted(&scene, &name, target, entry, inline).and_then(|(code, manifest, data)| {
        // A data form's pre-pass, for the page's device (`sdfc.seed` gives its input).
        let prune = if data { prune_shader(&scene)? } else { None };
        Ok((code, manifest, prune))
    });
    match made {
        Ok((code, manifest, prune)) => {
            LAST_VOLUMES.with(|v| *v.borrow_mut() = scene.volumes());
            response["ok"] = json!(true);
            response["code"] = json!(code);
            response["manifest"] = manifest;
            response["prune"] = json!(prune);
        }
        Err(e) => response["error"] = json!(format!("internal compiler error: {e}")),
    }
    response.to_string()
}

thread_local! {
    /// The baked volumes of the last scene that compiled, for [`volume`].
    static LAST_VOLUMES: std::cell::RefCell<Vec<Arc<Volume>>> = const { std::cell::RefCell::new(Vec::new()) };
}

thread_local! {
    /// The last scene that compiled to the data form, for [`data_at`].
    static LAST_DATA: std::cell::RefCell<Option<Scene>> = const { std::cell::RefCell::new(None) };
}

/// The last scene [`compile`] compiled as data at the parameter values of `request` (JSON
/// `{"name": [numbers], …}`; others at their defaults), with its tree and layout; `None` where
/// the last scene is not drawn as data, or where these values need another shader (the parts'
/// kinds, nesting or bounds changed).
fn valued_at(request: &str) -> Option<(Scene, sdfc_compiler::tape::Part, Layout)> {
    use sdfc_compiler::tape::data;
    let values: std::collections::HashMap<String, Vec<f64>> =
        serde_json::from_str(request).unwrap_or_default();
    LAST_DATA.with(|d| {
        let d = d.borrow();
        let scene = d.as_ref()?;
        let valued = scene.with_values(&values);
        let (_, compiled) = data::layout(scene, None).ok()?;
        let (tree, layout) = data::layout(&valued, None).ok()?;
        compiled.holds(&layout).then_some((valued, tree, layout))
    })
}

/// Byte arrays, each after its length (4 bytes, little-endian).
fn parts(parts: &[&[u8]]) -> Vec<u8> {
    let mut out = Vec::new();
    for b in parts {
        out.extend_from_slice(&(b.len() as u32).to_le_bytes());
        out.extend_from_slice(b);
    }
    out
}

/// Little-endian bytes of u32 words.
fn bytes_of(words: impl IntoIterator<Item = u32>) -> Vec<u8> {
    words.into_iter().flat_map(u32::to_le_bytes).collect()
}

/// The data form's three buffers (nodes, code, ranges: as `sdfc emit --form data` writes
/// them) for the last scene [`compile`] compiled as data, at the parameter values of
/// `request` (see [`valued_at`]), each after its length; `None` where there are none.
pub fn data_at(request: &str) -> Option<Vec<u8>> {
    let (valued, tree, layout) = valued_at(request)?;
    let made = sdfc_compiler::tape::data::data(&valued, &tree, &layout).ok()?;
    let [a, b, c] = made.buffers();
    Some(parts(&[&a, &b, &c]))
}

/// What the page's device pre-pass (the compile's `prune` shader) starts from for the last
/// scene compiled as data at the values of `request` (see [`valued_at`]; `tape::seed`), each
/// part after its length: the table, what the pre-pass knows of its parts, the whole and
/// outside programs, the ranges buffer's first contents, and per level its cells and its
/// uniform's words (the rooms and the first cell, at the compile's `room_words`, left 0 for
/// the page to fill in). `None` where there is none, or the scene has no grid.
pub fn seed_at(request: &str) -> Option<Vec<u8>> {
    let (valued, tree, layout) = valued_at(request)?;
    let seed = sdfc_compiler::tape::seed::seed(&valued, &tree, &layout).ok()??;
    let (ranges, bases) = seed.ranges();
    let mut levels = Vec::new();
    for (l, (n, _)) in seed.levels.iter().enumerate() {
        levels.push(n.iter().product::<usize>() as u32);
        levels.extend(seed.level_words(l, &bases, (0, 0, 0)));
    }
    let nodes = bytes_of(seed.nodes.iter().flatten().copied());
    let meta = bytes_of(seed.meta.iter().flatten().copied());
    Some(parts(&[
        &nodes,
        &meta,
        &bytes_of(seed.code.iter().copied()),
        &bytes_of(ranges),
        &bytes_of(levels),
    ]))
}

/// The data form's pre-pass for the device (`lower::prune`) as WGSL, with what a page needs to
/// run it (docs/playground.md): its workgroup, bindings, the level uniform's words and where
/// the host's rooms go in it, the overflow count of a cell that found no scratch, and the
/// rooms `sdfc render` gives (cells a dispatch, words a cell).
fn prune_shader(scene: &Scene) -> Result<Option<Value>, String> {
    use sdfc_compiler::layout::{PRUNE_BINDINGS, PRUNE_SCRATCH_MISSED, PRUNE_WORKGROUP};
    use sdfc_compiler::tape::seed::{
        CHUNK, LEVEL_WORDS, ROOM_PER_CELL, ROOM_WORDS, SCRATCH_PER_CELL,
    };
    let Some((module, info, _)) = emit::prune_module(scene).map_err(|e| e.0)? else {
        return Ok(None);
    };
    let Output::Text(code) =
        emit::write(&module, &info, Target::Wgsl, Entry::Compute).map_err(|e| e.0)?
    else {
        return Err("a binary output for WGSL".into());
    };
    Ok(Some(json!({
        "code": code,
        "workgroup": PRUNE_WORKGROUP,
        "bindings": PRUNE_BINDINGS,
        "level_words": LEVEL_WORDS,
        "room_words": ROOM_WORDS,
        "scratch_missed": PRUNE_SCRATCH_MISSED,
        "chunk": CHUNK,
        "room_per_cell": ROOM_PER_CELL,
        "scratch_per_cell": SCRATCH_PER_CELL,
    })))
}

/// Baked volume `index` of the last scene [`compile`] compiled, as the file `sdfc emit` writes
/// beside the shader (the manifest's `volumes[index].file`): what the page uploads.
pub fn volume(index: usize) -> Option<Vec<u8>> {
    LAST_VOLUMES.with(|v| {
        v.borrow()
            .get(index)
            .map(|v| sdfc_compiler::bake::file::raw(v))
    })
}

/// The scene's tracer settings with the page's overrides (`{"name", "settings": {…}}`), or
/// the error `sdfc emit` gives for the same flags.
fn overridden(trace: Trace, asked: Option<&Value>) -> Result<Trace, String> {
    let Some(asked) = asked else {
        return Ok(trace);
    };
    let name = asked.get("name").and_then(Value::as_str);
    let values: Vec<(&str, &str)> = asked
        .get("settings")
        .and_then(Value::as_object)
        .map(|m| {
            m.iter()
                .filter_map(|(k, v)| Some((k.as_str(), v.as_str()?)))
                .collect()
        })
        .unwrap_or_default();
    check::tracer::with_overrides(trace, name, &values).map_err(|e| format!("error: {e}"))
}

/// Every tracer and its parameters' names: `[{"name", "params": […]}, …]`.
fn tracers() -> Value {
    check::tracer::TRACE_METHODS
        .iter()
        .map(|(name, _, params)| {
            json!({ "name": name, "params": params.iter().map(|p| p.name).collect::<Vec<_>>() })
        })
        .collect()
}

/// The target and entry asked for, or why they cannot be had.
fn choose((target, entry): &(String, String)) -> Result<(Target, Entry), String> {
    let entry = match entry.as_str() {
        "fragment" => Entry::Fragment,
        "compute" => Entry::Compute,
        "library" => Entry::Library,
        other => {
            return Err(format!(
                "unknown entry `{other}`: fragment, compute or library"
            ));
        }
    };
    let target = match target.as_str() {
        "wgsl" => Target::Wgsl,
        "glsl" if entry == Entry::Compute => {
            return Err("GLSL ES 3.00 (WebGL2) has no compute shaders".into());
        }
        "glsl" => Target::Glsl,
        other => return Err(format!("unknown target `{other}`: wgsl or glsl")),
    };
    Ok((target, entry))
}

/// The scene checked as `sdfc check` checks it at its defaults: the checker's diagnostics,
/// then the Lipschitz annotations verified at the defaults and over the parameters' ranges —
/// unless `later`, when the answer's last part says whether that check has work left.
fn checked(name: &str, source: &str, later: bool) -> (Checked, Vec<Diagnostic>, bool) {
    let at = |v: &Values| check::compile_file(name, source, v, &NoFiles);
    let checked = at(&Values::new());
    let mut diagnostics = checked.diagnostics.clone();
    if later {
        let pending = checked.scene.as_ref().is_some_and(lipschitz::has_claims);
        return (checked, diagnostics, pending);
    }
    if let Some(scene) = &checked.scene {
        let at_values = |v: &Values| at(v).scene;
        diagnostics.extend(lipschitz::verify_everywhere(
            &at_values,
            scene,
            Effort::Fast,
            &Values::new(),
        ));
    }
    (checked, diagnostics, false)
}

/// The shader and its manifest, as `sdfc emit FILE --target … --entry … --manifest` writes them
/// (baked volumes named as `emit` would write them beside `NAME.wgsl`; the page is not given
/// their bytes yet), and whether it is the data form.
fn emitted(
    scene: &Scene,
    name: &str,
    target: Target,
    entry: Entry,
    inline: bool,
) -> Result<(String, Value, bool), String> {
    let mut options = Options::from_scene(scene);
    // WebGPU draws a scene of many parts as data, as `sdfc render` does (`--form auto`): the
    // page asks for its buffers at the sliders' values (`data_at`). WebGL2 has no storage
    // buffers: inline there.
    let data = !inline
        && target == Target::Wgsl
        && sdfc_compiler::tape::data::prefer(scene)
        && sdfc_compiler::tape::data::layout(scene, None).is_ok();
    if data {
        options.form = sdfc_compiler::lower::tracer::Form::Data;
        // (Only a data form replaces it: an inline compile between, a download's, leaves the
        // drawn scene's buffers to be made.)
        LAST_DATA.with(|d| *d.borrow_mut() = Some(scene.clone()));
    }
    let (module, info) = emit::module(scene, entry, &options).map_err(|e| e.0)?;
    let settings = emit::Settings {
        glsl_version: GlslVersion::Es300,
        ..emit::Settings::default()
    };
    let (out, reflection) =
        emit::write_reflected(&module, &info, target, entry, &settings).map_err(|e| e.0)?;
    let stem = std::path::Path::new(name)
        .file_stem()
        .map_or("scene".into(), |s| s.to_string_lossy().into_owned());
    let volume_files: Vec<String> = (0..scene.volumes().len())
        .map(|i| sdfc_compiler::bake::file::raw_name(&stem, i))
        .collect();
    let origin = sdfc_compiler::manifest::Origin {
        volume_files: &volume_files,
        data: None,
        scene: name,
        target: if target == Target::Wgsl {
            "wgsl"
        } else {
            "glsl"
        },
        entry,
        prefix: None,
        written: Some((&out, &reflection)),
    };
    let manifest = sdfc_compiler::manifest::manifest(scene, &module, &origin);
    match out {
        Output::Text(code) => Ok((code, manifest, data)),
        Output::Binary(_) => Err("a binary output for a text target".into()),
    }
}

/// Memory for `len` bytes the page writes its request into; give it back with [`sdfc_free`].
#[unsafe(no_mangle)]
pub extern "C" fn sdfc_alloc(len: usize) -> *mut u8 {
    let mut bytes = Vec::<u8>::with_capacity(len.max(1));
    let at = bytes.as_mut_ptr();
    std::mem::forget(bytes);
    at
}

/// Gives back memory from [`sdfc_alloc`] or [`sdfc_compile`] (`len` as allocated).
///
/// # Safety
/// `at` and `len` must be what one of those returned (and said), not given back before.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sdfc_free(at: *mut u8, len: usize) {
    // SAFETY: the caller gives back an allocation of capacity `len.max(1)` made by a Vec.
    drop(unsafe { Vec::from_raw_parts(at, 0, len.max(1)) });
}

/// Compiles the request of `len` bytes at `at` (UTF-8 JSON, see [`compile`]); returns memory
/// holding the response's length (4 bytes, little-endian) and its UTF-8 JSON. Free it with
/// [`sdfc_free`] and 4 + that length.
///
/// # Safety
/// `at` must point at `len` readable bytes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sdfc_compile(at: *const u8, len: usize) -> *mut u8 {
    // SAFETY: the caller wrote `len` bytes at `at`.
    let request = unsafe { std::slice::from_raw_parts(at, len) };
    let response = compile(&String::from_utf8_lossy(request));
    handed_over(response.as_bytes())
}

/// The raw bytes (`r32float` texels, x fastest: the file `sdfc emit` writes) of baked volume
/// `index` of the last scene that compiled, as [`sdfc_compile`] hands over its response (4
/// bytes of length, then the bytes; free with [`sdfc_free`]); null where there is none.
#[unsafe(no_mangle)]
pub extern "C" fn sdfc_volume(index: usize) -> *mut u8 {
    match volume(index) {
        Some(bytes) => handed_over(&bytes),
        None => std::ptr::null_mut(),
    }
}

/// [`data_at`] for the values of the request of `len` bytes at `at` (UTF-8 JSON), handed over
/// as [`sdfc_compile`] hands over its response; null where there are none.
///
/// # Safety
/// `at` must point at `len` readable bytes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sdfc_data(at: *const u8, len: usize) -> *mut u8 {
    // SAFETY: the caller's promise, passed on.
    unsafe { answered(at, len, data_at) }
}

/// [`seed_at`] for the values of the request of `len` bytes at `at` (UTF-8 JSON), handed over
/// as [`sdfc_compile`] hands over its response; null where there is none.
///
/// # Safety
/// `at` must point at `len` readable bytes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sdfc_seed(at: *const u8, len: usize) -> *mut u8 {
    // SAFETY: the caller's promise, passed on.
    unsafe { answered(at, len, seed_at) }
}

/// `answer` of the request of `len` bytes at `at` (UTF-8 JSON), handed over as
/// [`sdfc_compile`] hands over its response; null where there is none.
///
/// # Safety
/// `at` must point at `len` readable bytes.
unsafe fn answered(at: *const u8, len: usize, answer: fn(&str) -> Option<Vec<u8>>) -> *mut u8 {
    // SAFETY: the caller wrote `len` bytes at `at`.
    let request = unsafe { std::slice::from_raw_parts(at, len) };
    match answer(&String::from_utf8_lossy(request)) {
        Some(bytes) => handed_over(&bytes),
        None => std::ptr::null_mut(),
    }
}

/// `bytes` in new memory after their length (4 bytes, little-endian), for the page to read and
/// give back with [`sdfc_free`] (capacity 4 + the length).
fn handed_over(bytes: &[u8]) -> *mut u8 {
    let mut out = Vec::with_capacity(4 + bytes.len());
    out.extend_from_slice(&(bytes.len() as u32).to_le_bytes());
    out.extend_from_slice(bytes);
    debug_assert_eq!(out.capacity(), 4 + bytes.len());
    let at = out.as_mut_ptr();
    std::mem::forget(out);
    at
}
