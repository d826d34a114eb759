//! `sdfc mesh`: a scene's surface as a closed triangle mesh in STL, OBJ, PLY or glTF, with how
//! far it lies from the surface.

use super::common::{progress_bar, writable, write_output};
use crate::cli::input::{exit_code, load_scene_with, param_values};
use crate::cli::messages::{self, done};
use crate::cli::values::{MeshBackendArg, MeshMethodArg};
use crate::cli::{Error, MeshArgs};
use glam::DVec3;
use sdfc::gpu::BackendChoice;
use sdfc::mesh_gpu::GpuField;
use sdfc_compiler::diag::Diagnostic;
use sdfc_compiler::mesh::field::{Evaluator, Field};
use sdfc_compiler::mesh::formats::{self, Format};
use sdfc_compiler::mesh::{self, Mesh, measure};
use sdfc_compiler::scene::Scene;
use std::path::Path;
use std::time::Instant;

/// Runs `sdfc mesh`; returns the exit code.
pub fn run(args: &MeshArgs) -> i32 {
    crate::keep_freed_memory();
    exit_code(mesh_scene(args))
}

/// How much the scene's own box is grown, relative to its longest side, so that no surface
/// lies on the cut.
const GROW: f64 = 0.01;

fn mesh_scene(args: &MeshArgs) -> Result<(), Error> {
    let started = Instant::now();
    let format = output_format(args)?;
    writable(&args.output)?;
    let mut values = param_values(&args.params, args.time)?;
    values.bake_res = args.bake.bake_res;
    let Some((sources, scene)) = load_scene_with(&args.file, &values) else {
        return Err(Error::Reported);
    };
    let scene = scene.with_values(&values.values);
    let bounds = match &args.bounds {
        Some(text) => parse_bounds(text)?,
        None => own_bounds(&scene, &sources)?,
    };
    let longest = (bounds.1 - bounds.0).max_element();
    let resolution = match args.cell {
        Some(c) if c.is_finite() && c > 0.0 => {
            let r = longest / c;
            if !(1.0..=f64::from(mesh::MAX_RESOLUTION)).contains(&r) {
                return Err(format!(
                    "error: `--cell {c}`: {r:.0} cells along the box's longest side ({longest}); \
                     give a size from {:.3e} to {longest}",
                    longest / f64::from(mesh::MAX_RESOLUTION)
                )
                .into());
            }
            r
        }
        Some(c) => return Err(format!("error: `--cell {c}`: give a size above 0").into()),
        None => f64::from(args.resolution),
    };
    if !(args.max_memory.is_finite() && args.max_memory > 0.0) {
        return Err("error: `--max-memory`: give a size above 0 (GiB)".into());
    }
    let mut options = mesh::Options {
        resolution,
        bounds,
        sharp: args.method == MeshMethodArg::Sharp,
        prune: !args.no_prune,
        max_bytes: (args.max_memory * (1u64 << 30) as f64) as u64,
    };
    let gpu = gpu_field(args.backend, &scene, bounds)?;
    let evaluator = gpu.as_ref().map(|g| g as &dyn Evaluator);
    let bar = progress_bar("meshing");
    let t0 = Instant::now();
    let stage = |what: &str| {
        if args.stats {
            say!("{:8.3} s  {what}", t0.elapsed().as_secs_f64());
        }
        if let Some(b) = &bar {
            b.set_message(what.to_string());
        }
    };
    let mesh = match args.triangles {
        Some(n) => toward_count(&scene, &mut options, n, evaluator, &stage)?,
        None => mesh::mesh_with(&scene, &options, evaluator, &stage)
            .map_err(|e| format!("error: {e}"))?,
    };
    if mesh.triangles.is_empty() {
        return Err("error: no surface crosses the box: nothing to mesh (see `--bounds`)".into());
    }
    if args.stats {
        let s = mesh.stats;
        say!(
            "           {} cells contoured ({} of them the bound had pruned wrongly), {} edges \
             crossed twice, {} field evaluations",
            s.active_cells,
            s.added_cells,
            s.dipped_edges,
            s.evaluations
        );
    }
    stage("measuring");
    let field = Field::new(&scene, bounds.0, bounds.1).with_evaluator(evaluator);
    let deviation = measure::deviation(&field, &mesh, mesh.stats.cell);
    let topology = measure::topology(&mesh);
    stage("writing");
    write(&scene, &mesh, format, &args.output)?;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let on = match &gpu {
        Some(g) => format!("field on {} (f32)", g.device_name()),
        None => "field on the CPU (f64)".to_string(),
    };
    done(&success(args, &mesh, &topology, &deviation, started, &on));
    if !topology.is_closed_manifold() {
        say!(
            "warning: the mesh is not closed and 2-manifold: {} open, {} shared by more than two \
             triangles, {} misoriented edges, {} vertices sharing a position, {} cells left out \
             (a field that is not a function of the point: NaN)",
            topology.boundary,
            topology.non_manifold,
            topology.misoriented,
            topology.shared_positions,
            mesh.stats.broken_cells
        );
    }
    Ok(())
}

/// Fewest primitive evaluations a point for which `--backend auto` evaluates on the GPU:
/// below, opening a device and compiling the field cost more than they save (measured in
/// docs/mesh.md).
const GPU_FROM: f64 = 16.0;

/// The GPU field `--backend` asks for: `auto` opens one for a costly scene (none if it cannot),
/// `vulkan` and `gl` must.
fn gpu_field(
    backend: MeshBackendArg,
    scene: &Scene,
    bounds: (DVec3, DVec3),
) -> Result<Option<GpuField>, Error> {
    let choice = match backend {
        MeshBackendArg::Cpu => return Ok(None),
        MeshBackendArg::Auto if scene.root_node().evaluations < GPU_FROM => return Ok(None),
        MeshBackendArg::Auto => return Ok(GpuField::new(scene, BackendChoice::Auto, bounds).ok()),
        MeshBackendArg::Vulkan => BackendChoice::Vulkan,
        MeshBackendArg::Gl => BackendChoice::Gl,
    };
    GpuField::new(scene, choice, bounds).map(Some).map_err(|e| {
        format!(
            "error: no GPU to evaluate the field on: {e} (`--backend cpu` evaluates it on the CPU)"
        )
        .into()
    })
}

/// Coarsest and finest resolutions `--triangles` chooses from.
const COUNT_RESOLUTIONS: (f64, f64) = (4.0, 4096.0);

/// Meshes `--triangles` makes at most after its probe; more, up to [`CHEAP_RUNS`], while the
/// resolution is at most [`CHEAP`] cells (milliseconds each, and where counts jump most).
const COUNT_RUNS: usize = 3;

/// See [`COUNT_RUNS`].
const CHEAP_RUNS: usize = 8;

/// See [`COUNT_RUNS`].
const CHEAP: f64 = 32.0;

/// Resolution of the probe mesh `--triangles` counts first.
const PROBE: f64 = 24.0;

/// The mesh nearest `target` triangles: a probe at [`PROBE`] cells, then, while the nearest
/// count is more than 10 % off (at most [`COUNT_RUNS`] meshes, or [`CHEAP_RUNS`] of at most
/// [`CHEAP`] cells), the resolution the nearest
/// count predicts (triangles grow with its square; a resolution need not be whole, the cell
/// being the box's longest side over it) — kept between the nearest resolutions tried below and
/// above the target, their geometric mean where the prediction falls outside (counts jump
/// between coarse resolutions, where the grid's placement decides which cells a small part
/// crosses). `options.resolution` is left at the one used.
fn toward_count(
    scene: &Scene,
    options: &mut mesh::Options,
    target: u64,
    evaluator: Option<&dyn Evaluator>,
    stage: &dyn Fn(&str),
) -> Result<Mesh, Error> {
    if target < 4 {
        return Err(format!("error: `--triangles {target}`: a closed mesh has at least 4").into());
    }
    let (least, most) = COUNT_RESOLUTIONS;
    let run = |resolution: f64| {
        let o = mesh::Options {
            resolution,
            ..*options
        };
        mesh::mesh_with(scene, &o, evaluator, stage).map_err(|e| Error::from(format!("error: {e}")))
    };
    let predict =
        |r: f64, got: usize| (r * (target as f64 / got.max(1) as f64).sqrt()).clamp(least, most);
    let probe = run(PROBE)?;
    if probe.triangles.is_empty() {
        return Ok(probe);
    }
    let off = |m: &Mesh| (m.triangles.len() as f64 / target as f64 - 1.0).abs();
    // Every resolution tried and its count; the mesh nearest the target so far.
    let mut tried: Vec<(f64, usize)> = vec![(PROBE, probe.triangles.len())];
    let (mut mesh, mut r) = (probe, PROBE);
    for k in 0..CHEAP_RUNS {
        if off(&mesh) <= 0.1 {
            break;
        }
        let mut again = predict(r, mesh.triangles.len());
        let side = |below: bool| {
            tried
                .iter()
                .filter(move |t| (t.1 < target as usize) == below && t.1 != target as usize)
                .map(|t| t.0)
        };
        let below = side(true).max_by(f64::total_cmp);
        let above = side(false).min_by(f64::total_cmp);
        if let (Some(lo), Some(hi)) = (below, above)
            && !(again > lo.min(hi) && again < lo.max(hi))
        {
            again = (lo * hi).sqrt();
        }
        if tried.iter().any(|&(t, _)| t == again) || (k >= COUNT_RUNS && again > CHEAP) {
            break;
        }
        let other = run(again)?;
        tried.push((again, other.triangles.len()));
        if off(&other) < off(&mesh) {
            (mesh, r) = (other, again);
        }
    }
    options.resolution = r;
    Ok(mesh)
}

/// The format `--format` or the output's extension names.
fn output_format(args: &MeshArgs) -> Result<Format, Error> {
    let ext = args
        .output
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("");
    let format = match args.format {
        Some(f) => f.into(),
        None => Format::from_extension(ext).ok_or_else(|| {
            format!(
                "error: `{}`: name a mesh file `.stl`, `.obj`, `.ply` or `.glb` (or give \
                 `--format`)",
                args.output.display()
            )
        })?,
    };
    if format == Format::Obj && args.output == Path::new("-") {
        return Err("error: an OBJ file needs its MTL file beside it: write it to a file".into());
    }
    Ok(format)
}

/// `X0,Y0,Z0,X1,Y1,Z1` as the box's corners.
fn parse_bounds(text: &str) -> Result<(DVec3, DVec3), Error> {
    let bad = || {
        Error::from(format!(
            "error: `--bounds {text}`: give six numbers `X0,Y0,Z0,X1,Y1,Z1`, each lower corner \
             below the upper one"
        ))
    };
    let v: Vec<f64> = text
        .split(',')
        .map(|x| x.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| bad())?;
    if v.len() != 6 || v.iter().any(|x| !x.is_finite()) {
        return Err(bad());
    }
    let (lo, hi) = (DVec3::new(v[0], v[1], v[2]), DVec3::new(v[3], v[4], v[5]));
    if !lo.cmplt(hi).all() {
        return Err(bad());
    }
    Ok((lo, hi))
}

/// The scene's own box, grown by [`GROW`]; an unbounded scene is an error at the part that has
/// no bound.
fn own_bounds(
    scene: &Scene,
    sources: &sdfc_compiler::source::Sources,
) -> Result<(DVec3, DVec3), Error> {
    if let Some((lo, hi)) = mesh::scene_bounds(scene) {
        let grow = GROW * (hi - lo).max_element();
        return Ok((lo - grow, hi + grow));
    }
    let unbounded = scene.reachable().into_iter().find(|&id| {
        let n = &scene.nodes[id];
        !n.bound.is_finite()
            && n.children()
                .iter()
                .all(|&c| scene.nodes[c].bound.is_finite())
    });
    let Some(id) = unbounded else {
        return Err("error: the scene has no finite box: give one with `--bounds`".into());
    };
    let node = &scene.nodes[id];
    let d = Diagnostic::error(
        node.call_site.unwrap_or(node.span),
        format!(
            "`{}` is unbounded: the scene has no finite box to mesh",
            node.kind_name()
        ),
    )
    .label("this extends without end")
    .help(
        "give the box to mesh: `--bounds X0,Y0,Z0,X1,Y1,Z1` (the surface is cut and capped there)",
    );
    say_raw!("{}", messages::report(&[d], sources));
    Err(Error::Reported)
}

/// Writes the mesh (an OBJ's MTL beside it, named after it).
fn write(scene: &Scene, mesh: &Mesh, format: Format, out: &Path) -> Result<(), Error> {
    let bytes = match format {
        Format::Stl => formats::stl(mesh),
        Format::Ply => formats::ply(
            mesh,
            &formats::vertex_colors(scene, mesh, 1e-4 * mesh.stats.cell),
        ),
        Format::Glb => formats::glb(mesh, scene),
        Format::Obj => {
            let mtl_path = out.with_extension("mtl");
            let mtl_name = mtl_path.file_name().map_or_else(
                || "materials.mtl".to_string(),
                |n| n.to_string_lossy().into_owned(),
            );
            let (obj, mtl) = formats::obj(mesh, scene, &mtl_name);
            crate::cli::write_file(&mtl_path, mtl.as_bytes())?;
            obj.into_bytes()
        }
    };
    if write_output(Some(out), &bytes, format != Format::Obj) != 0 {
        return Err(Error::Reported);
    }
    Ok(())
}

/// The success line: what was written, whether it is closed, what it cost and how near it is.
fn success(
    args: &MeshArgs,
    mesh: &Mesh,
    topology: &measure::Topology,
    d: &measure::Deviation,
    started: Instant,
    on: &str,
) -> String {
    let place = match args.output.to_str() {
        Some("-") => "standard output".to_string(),
        _ => args.output.display().to_string(),
    };
    let shape = if topology.is_closed_manifold() {
        "closed, 2-manifold"
    } else {
        "NOT closed and 2-manifold"
    };
    let h = mesh.stats.cell;
    let g = mesh.stats.grid;
    // (Without pruning every cell is evaluated, near the surface or not.)
    let cells = match args.no_prune {
        false => "near the surface",
        true => "evaluated, no pruning",
    };
    let asked = match args.triangles {
        Some(n) => format!(
            " ({n} asked for: resolution {:.2} chosen)",
            mesh.stats.resolution
        ),
        None => String::new(),
    };
    format!(
        "wrote {place} — {} triangles{asked}, {} vertices, {shape}; cells of {h:.3e} ({}×{}×{}, {} \
         {cells}), {:.1} s; distance to the surface: vertices ≤ {:.1e}, faces ≤ {:.1e} \
         (rms {:.1e}, {} sampled) = {:.3} of a cell; {on}",
        mesh.triangles.len(),
        mesh.positions.len(),
        g[0],
        g[1],
        g[2],
        mesh.stats.active_cells,
        started.elapsed().as_secs_f64(),
        d.vertex_max,
        d.face_max,
        d.face_rms,
        d.faces_sampled,
        d.vertex_max.max(d.face_max) / h
    )
}
