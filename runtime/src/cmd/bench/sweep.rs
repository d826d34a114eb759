//! `sdfc bench --bake-sweep`: a scene measured at several `bake` resolutions and its analytic
//! form, against one ground truth (Liktor's Table 1), and the rows of its baked parts.

use super::{Planned, measure, plan};
use crate::cli::input::load_scene;
use crate::cli::{BenchArgs, Error};
use sdfc::bench::Cell;
use sdfc::gpu::Gpu;
use sdfc_compiler::lower::tracer::BoundingVolumes;
use sdfc_compiler::scene::Scene;
use sdfc_compiler::view::View;
use serde::Serialize;

/// Every form: the scene at each of `resolutions`, then `truth` itself, each measured with
/// every tracer and budget against the truth's `depth`.
pub(super) fn measure_all(
    (args, bvh): (&BenchArgs, BoundingVolumes),
    gpu: &Gpu,
    (resolutions, truth): (&[u32], &Scene),
    (view, depth): (&View, &[Option<f64>]),
    reference: Option<(&str, &str)>,
) -> Result<Vec<Swept>, Error> {
    let mut swept = Vec::new();
    for bake_res in resolutions.iter().map(|&n| Some(n)).chain([None]) {
        let at = match bake_res {
            Some(n) => load_scene(&args.file, Some(n)).ok_or(Error::Reported)?.1,
            None => truth.clone(),
        };
        let cells: Vec<Planned> = plan(args, &at)?;
        gpu.set_scene(&at);
        let cells = measure((args, bvh), gpu, (&at, view, depth), &cells, reference)?;
        swept.push(Swept {
            bake_res,
            volumes: at.volumes().iter().map(Baked::of).collect(),
            cells,
        });
    }
    Ok(swept)
}

/// One form of the scene in a `--bake-sweep`: every `bake` at `bake_res`, or (`None`) the
/// `--truth` scene as written.
#[derive(Serialize)]
pub(super) struct Swept {
    bake_res: Option<u32>,
    volumes: Vec<Baked>,
    cells: Vec<Cell>,
}

/// A baked part: its map's size, memory, λ and how long it took to bake.
#[derive(Serialize)]
pub(super) struct Baked {
    /// Points along x, y and z.
    pub(super) points: [usize; 3],
    /// Its spacing in scene units.
    pub(super) spacing: f64,
    /// Bytes on the GPU (one f32 per point).
    pub(super) bytes: u64,
    /// The map's proven Lipschitz constant.
    pub(super) lambda: f64,
    /// Seconds its bake took in this process (sampling, distance transform, λ), on the CPU.
    pub(super) bake_seconds: Option<f64>,
}

impl Baked {
    pub(super) fn of(v: &std::sync::Arc<sdfc_compiler::bake::Volume>) -> Baked {
        Baked {
            points: v.grid.n,
            spacing: v.grid.h,
            bytes: v.bytes(),
            lambda: v.lambda,
            bake_seconds: sdfc_compiler::bake::cache::bake_seconds(v),
        }
    }
}

/// `--bake-sweep`'s resolutions, each within `bake`'s range.
pub(super) fn resolutions(list: &str) -> Result<Vec<u32>, Error> {
    let range = sdfc_compiler::bake::MIN_RES..=sdfc_compiler::bake::MAX_RES;
    let out: Vec<u32> = super::split(list)
        .iter()
        .map(|s| {
            s.parse::<u32>()
                .ok()
                .filter(|n| range.contains(&(*n as usize)))
        })
        .collect::<Option<_>>()
        .ok_or_else(|| {
            format!(
                "error: `--bake-sweep {list}`: give whole numbers from {} to {}, comma-separated",
                range.start(),
                range.end()
            )
        })?;
    if out.is_empty() {
        return Err("error: `--bake-sweep` needs at least one resolution".into());
    }
    Ok(out)
}

/// `--bake-sweep`'s table: per form (each resolution, then analytic) its parts' bake time and
/// memory, and per tracer and budget its time, evaluations and error (Liktor's Table 1).
pub(super) fn table(sweep: &[Swept]) -> String {
    let mut out = format!(
        "{:<12} {:>20} {:>9} {:>8} {:>9} {:>6} {:>9} {:>9} {:>10} {:>11} {:>9}\n",
        "form",
        "points",
        "MiB",
        "bake s",
        "tracer",
        "steps",
        "trace ms",
        "frame ms",
        "evals/px",
        "depth MSE",
        "hit/miss"
    );
    for s in sweep {
        let form = match s.bake_res {
            Some(n) => format!("baked {n}"),
            None if s.volumes.is_empty() => "analytic".to_string(),
            None => "--truth".to_string(),
        };
        let points = s
            .volumes
            .iter()
            .map(|v| format!("{}×{}×{}", v.points[0], v.points[1], v.points[2]))
            .collect::<Vec<_>>()
            .join(" + ");
        let mib: f64 =
            s.volumes.iter().map(|v| v.bytes as f64).sum::<f64>() / f64::from(1u32 << 20);
        let secs: Option<f64> = s.volumes.iter().map(|v| v.bake_seconds).sum();
        let (mib, secs) = match s.volumes.is_empty() {
            true => ("—".to_string(), "—".to_string()),
            false => (
                format!("{mib:.1}"),
                secs.map_or("cached".to_string(), |t| format!("{t:.2}")),
            ),
        };
        for (i, c) in s.cells.iter().enumerate() {
            let first = i == 0;
            out += &format!(
                "{:<12} {:>20} {:>9} {:>8} {:>9} {:>6} {:>9.3} {:>9.3} {:>10.2} {:>11.3e} {:>8.2}%\n",
                if first { form.as_str() } else { "" },
                if first { points.as_str() } else { "" },
                if first { mib.as_str() } else { "" },
                if first { secs.as_str() } else { "" },
                c.tracer,
                c.steps,
                c.seconds * 1e3,
                c.frame_seconds * 1e3,
                c.evals_mean,
                c.mse,
                c.mismatch * 100.0
            );
        }
    }
    out
}
