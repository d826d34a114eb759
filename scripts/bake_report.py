"""Writes the measured tables of docs/bake.md (between its `<!-- bench:start -->` and
`<!-- bench:end -->` markers) from `sdfc bench --bake-sweep … --json` output.

Usage: python3 scripts/bake_report.py RUN.json docs/bake.md
"""
import json
import sys

run_path, doc_path = sys.argv[1:3]
run = json.load(open(run_path))
sweep = run["sweep"]
budgets = [c["steps"] for c in sweep[0]["cells"]]


def form(s):
    return f"baked {s['bake_res']}" if s["bake_res"] else "analytic"


def ms(x):
    return f"{x * 1e3:.1f}"


out = []
w = out.append
w(f"Measured by `bash scripts/bake_bench.sh` on {run['adapter']} ({run['backend']}), "
  f"{run['width']}×{run['height']}, median of {run['repeat']} frames; truth: the f64 field of "
  f"`{run['truth_scene']}` ({run['truth']['pixels'] - run['truth']['escaped']} of "
  f"{run['truth']['pixels']} pixels hit it; {run['truth']['seconds']:.0f} s on the CPU). Raw "
  f"numbers: `docs/bake/fluid.json`.")
w("")
w("**Trace time (ms) per frame, basic tracer, by step budget** — Liktor's Table 1 gives frames")
w("per second by grid resolution and iterations:")
w("")
w("| form | points | memory | bake | " + " | ".join(f"{b} steps" for b in budgets) + " |")
w("| --- | --- | ---: | ---: | " + " | ".join("---:" for _ in budgets) + " |")
for s in sweep:
    vols = s["volumes"]
    pts = " + ".join("×".join(str(n) for n in v["points"]) for v in vols) or "—"
    mem = f"{sum(v['bytes'] for v in vols) / 2**20:.1f} MiB" if vols else "—"
    secs = [v["bake_seconds"] for v in vols]
    bake = f"{sum(secs):.1f} s" if vols and None not in secs else "—"
    w(f"| {form(s)} | {pts} | {mem} | {bake} | " + " | ".join(ms(c["seconds"]) for c in s["cells"]) + " |")
w("")
w("**Depth error against the analytic surface: mean squared depth error (scene units²) / share of")
w("pixels whose hit or miss differs**, same runs:")
w("")
w("| form | λ | " + " | ".join(f"{b} steps" for b in budgets) + " |")
w("| --- | ---: | " + " | ".join("---:" for _ in budgets) + " |")
for s in sweep:
    lam = ", ".join(f"{v['lambda']:.2f}" for v in s["volumes"]) or "1 (blob)"
    cells = " | ".join(f"{c['mse']:.2e} / {c['mismatch'] * 100:.2f}%" for c in s["cells"])
    w(f"| {form(s)} | {lam} | {cells} |")
w("")
w("**Depth error of the surface found, where both the ray and the truth hit: median / 99th")
w("percentile of |t − t_truth|, in cells of the map** (analytic: in scene units) — without the")
w("pixels whose hit differs, which dominate the mean squared error above:")
w("")
w("| form | cell | " + " | ".join(f"{b} steps" for b in budgets) + " |")
w("| --- | ---: | " + " | ".join("---:" for _ in budgets) + " |")
for s in sweep:
    h = s["volumes"][0]["spacing"] if s["volumes"] else None
    unit = h or 1.0
    # (All zeros: no pixel where both hit.)
    cells = " | ".join(
        f"{c['hit_depth_error'][0] / unit:.3g} / {c['hit_depth_error'][1] / unit:.3g}"
        if any(c["hit_depth_error"]) else "—"
        for c in s["cells"]
    )
    w(f"| {form(s)} | {f'{h:.4f}' if h else '—'} | {cells} |")
w("")
w("**Evaluations per pixel** (each baked one reads 8 texels; each analytic one sums 200 falloffs):")
w("")
w("| form | " + " | ".join(f"{b} steps" for b in budgets) + " |")
w("| --- | " + " | ".join("---:" for _ in budgets) + " |")
for s in sweep:
    w(f"| {form(s)} | " + " | ".join(f"{c['evals_mean']:.1f}" for c in s["cells"]) + " |")

doc = open(doc_path).read()
start, end = "<!-- bench:start -->\n", "<!-- bench:end -->"
a = doc.index(start) + len(start)
b = doc.index(end)
open(doc_path, "w").write(doc[:a] + "\n".join(out) + "\n" + doc[b:])
