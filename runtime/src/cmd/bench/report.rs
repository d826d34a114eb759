//! `sdfc bench`'s report as the user asked for it: the table, JSON or CSV, and the plot.

use super::{Report, sweep};
use crate::cli::input::print_out;
use crate::cli::{BenchArgs, Error};
use sdfc::bench::Cell;

/// Draws the plot (if asked for) and prints the report as asked: JSON, CSV or the table.
pub(super) fn print(args: &BenchArgs, report: &Report) -> Result<(), Error> {
    if let Some(p) = args.plot.as_deref() {
        let title = format!(
            "{}: {}×{} on {}",
            report.scene, report.width, report.height, report.adapter
        );
        sdfc::bench::plot::write(p, &title, &report.cells)?;
    }
    let text = if args.json {
        let text = serde_json::to_string_pretty(report)
            .map_err(|e| Error::Usage(format!("error: {e}")))?;
        format!("{text}\n")
    } else if args.csv {
        csv(&report.cells)
    } else {
        table(report)
    };
    // A closed pipe ends quietly; a full device was reported already.
    match print_out(&text) {
        Ok(()) | Err(0) => Ok(()),
        Err(_) => Err(Error::Reported),
    }
}

fn csv(cells: &[Cell]) -> String {
    let mut out = String::from(
        "tracer,steps,passes,seconds,frame_seconds,evals_mean,evals_max,shading_evals_mean,mse,mismatch,error_x_time,reference_seconds,reference_evals_mean\n",
    );
    for c in cells {
        let (rs, re) = match &c.reference {
            Some(r) => (r.seconds.to_string(), r.evals_mean.to_string()),
            None => (String::new(), String::new()),
        };
        out += &format!(
            "{},{},{},{},{},{},{},{},{},{},{},{rs},{re}\n",
            c.tracer,
            c.steps,
            c.passes,
            c.seconds,
            c.frame_seconds,
            c.evals_mean,
            c.evals_max,
            c.shading_evals_mean,
            c.mse,
            c.mismatch,
            c.error_x_time
        );
    }
    out
}

/// The table's lines about the scene's parts: each baked part, the data form's pre-pass.
fn parts(r: &Report) -> String {
    let mut out = String::new();
    for (i, v) in r.volumes.iter().enumerate() {
        let [x, y, z] = v.points;
        let took = v
            .bake_seconds
            .map_or("read from the cache".to_string(), |s| {
                format!("baked in {s:.2} s")
            });
        out += &format!(
            "baked part {i}: {x}×{y}×{z} points, spacing {:.4}, {:.1} MiB, λ {:.3}, {took}\n",
            v.spacing,
            v.bytes as f64 / f64::from(1u32 << 20),
            v.lambda
        );
    }
    if let Some(p) = &r.prepass {
        out += &format!(
            "form: data — pre-pass on the {} {:.1} ms{}, {} cells, {:.1} leaves a cell, {:.1} MiB of buffers\n",
            p.ran_on.to_uppercase(),
            p.seconds * 1e3,
            match p.ran_on {
                "gpu" => format!(
                    " (its pipeline compiled in {:.1} ms; run again with more room {} times)",
                    p.compile_seconds * 1e3,
                    p.retries
                ),
                _ => String::new(),
            },
            p.cells,
            p.mean_leaves,
            p.bytes as f64 / f64::from(1u32 << 20)
        );
    }
    if r.truth_scene.is_some() || !r.volumes.is_empty() || r.prepass.is_some() {
        out += "\n";
    }
    out
}

fn table(r: &Report) -> String {
    let truth = match r.truth.steps {
        0 => "ground truth: none (`--no-truth`), so no errors".to_string(),
        _ => format!(
            "ground truth: basic, {} steps, ε {}·|eye − target|, {} bisections; {} of {} pixels escape (CPU {:.1} s)",
            r.truth.steps,
            r.truth.epsilon,
            r.truth.bisections,
            r.truth.escaped,
            r.truth.pixels,
            r.truth.seconds
        ),
    };
    let mut out = format!(
        "{}: {}×{} on {} ({})\n{truth}\ntime: {}\n\n",
        r.scene, r.width, r.height, r.adapter, r.backend, r.timing
    );
    if let Some(t) = &r.truth_scene {
        out += &format!("truth: the f64 field of {t}\n");
    }
    if !r.sweep.is_empty() {
        return out + &sweep::table(&r.sweep);
    }
    out += &parts(r);
    out += &format!(
        "{:<9} {:>6} {:>6} {:>9} {:>9} {:>10} {:>9} {:>9} {:>11} {:>9} {:>11}\n",
        "tracer",
        "steps",
        "passes",
        "trace ms",
        "frame ms",
        "evals/px",
        "max",
        "+shading",
        "depth MSE",
        "hit/miss",
        "err×time"
    );
    for c in &r.cells {
        out += &format!(
            "{:<9} {:>6} {:>6} {:>9.3} {:>9.3} {:>10.2} {:>9} {:>9.2} {:>11.3e} {:>8.2}% {:>11.3e}\n",
            c.tracer,
            c.steps,
            c.passes,
            c.seconds * 1e3,
            c.frame_seconds * 1e3,
            c.evals_mean,
            c.evals_max,
            c.shading_evals_mean,
            c.mse,
            c.mismatch * 100.0,
            c.error_x_time
        );
        if let Some([traced, shaded]) = c.primitives {
            out += &format!(
                "{:<9} {:>6} {:>6}   primitive evaluations per pixel: {traced:.1} by the trace, +{shaded:.1} by shading\n",
                "", "", ""
            );
        }
        if let Some(x) = &c.reference {
            out += &format!(
                "{:<9} {:>6} {:>6} {:>9.3} {:>9} {:>10.2}   hit/miss agree with sdfc's on {:.2}%; sdfc / reference = {:.3}×\n",
                "  ref",
                "",
                "",
                x.seconds * 1e3,
                "",
                x.evals_mean,
                x.mask_agreement * 100.0,
                x.ratio
            );
        }
    }
    if let Some(e) = r.target_error {
        out += &match &r.fastest {
            Some(c) => format!(
                "\nfastest with depth MSE ≤ {e:e} and hit/miss differing on ≤ {:.1}% of pixels: {} with {} steps, {:.3} ms ({:.2} evaluations per pixel)\n",
                r.max_mismatch * 100.0,
                c.tracer,
                c.steps,
                c.seconds * 1e3,
                c.evals_mean
            ),
            None => format!(
                "\nno tracer and budget measured reaches depth MSE ≤ {e:e} with hit/miss differing on ≤ {:.1}% of pixels; try larger budgets\n",
                r.max_mismatch * 100.0
            ),
        };
    }
    out
}
