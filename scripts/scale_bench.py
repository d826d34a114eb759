#!/usr/bin/env python3
"""Measures how the data form and the inline form scale with the parts (issue 33).

Usage: scripts/scale_bench.py SDFC OUT_DIR [--sizes 10,100,1000,10000] [--inline-up-to 300]
                              [--size 320x180]

For each N and each union (smooth, hard), writes `scripts/spheres.py`'s scene into OUT_DIR and
runs, for each form (the inline one up to `--inline-up-to` parts: beyond, its shader takes
minutes to compile):

- `sdfc bench … --tracers basic --steps 128 --no-truth --count-primitives --json`: trace and
  frame time (GPU timestamps, median of 5), evaluations and primitive evaluations per pixel,
  the data form's CPU pre-pass;
- the first frame, cold: `sdfc render … --samples 1` with Mesa's shader cache off
  (`MESA_SHADER_CACHE_DISABLE=true`), wall time of the whole command.

Prints a Markdown table and writes OUT_DIR/scale.json.
"""

import argparse
import json
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def bench(sdfc, scene, size, form):
    cmd = [sdfc, "bench", scene, "--tracers", "basic", "--steps", "128", "--size", size,
           "--repeat", "5", "--no-truth", "--count-primitives", "--json", "--form", form]
    if form == "inline":
        cmd.append("--allow-slow-compile")
    out = subprocess.run(cmd, capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def cold(sdfc, scene, size, form, out_png):
    env = dict(os.environ, MESA_SHADER_CACHE_DISABLE="true")
    cmd = [sdfc, "render", scene, "--size", size, "--samples", "1", "--form", form,
           "-o", out_png]
    if form == "inline":
        cmd.append("--allow-slow-compile")
    t = time.time()
    subprocess.run(cmd, capture_output=True, text=True, check=True, env=env)
    return time.time() - t


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("sdfc")
    ap.add_argument("out")
    ap.add_argument("--sizes", default="10,100,1000,10000")
    ap.add_argument("--inline-up-to", type=int, default=300)
    ap.add_argument("--size", default="320x180")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    rows = []
    for n in [int(x) for x in a.sizes.split(",")]:
        for way in ["smooth", "hard"]:
            scene = os.path.join(a.out, f"{way}_{n}.sdf")
            subprocess.run([sys.executable, os.path.join(HERE, "spheres.py"), str(n), way,
                            "-o", scene], check=True)
            for form in ["inline", "data"]:
                if form == "inline" and n > a.inline_up_to:
                    continue
                r = bench(a.sdfc, scene, a.size, form)
                c = r["cells"][0]
                first = cold(a.sdfc, scene, a.size, form, os.path.join(a.out, f"{way}_{n}_{form}.png"))
                row = {
                    "n": n, "union": way, "form": form,
                    "trace_ms": c["seconds"] * 1e3, "frame_ms": c["frame_seconds"] * 1e3,
                    "evals": c["evals_mean"], "primitives": c["primitives"][0],
                    "shading_primitives": c["primitives"][1],
                    "prepass_ms": r["prepass"]["seconds"] * 1e3 if r.get("prepass") else None,
                    "leaves_per_cell": r["prepass"]["mean_leaves"] if r.get("prepass") else None,
                    "buffers_mib": r["prepass"]["bytes"] / 2**20 if r.get("prepass") else None,
                    "first_frame_s": first,
                }
                rows.append(row)
                print(json.dumps(row), file=sys.stderr, flush=True)
    with open(os.path.join(a.out, "scale.json"), "w") as f:
        json.dump(rows, f, indent=1)
    print("| N | union | form | trace (ms) | frame (ms) | evals / px | primitive evals / px (trace + shading) | pre-pass (ms) | leaves / cell | buffers (MiB) | first frame, cold (s) |")
    print("| ---: | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    fmt = lambda x, d: "—" if x is None else f"{x:.{d}f}"
    for r in rows:
        print(f"| {r['n']} | {r['union']} | {r['form']} | {r['trace_ms']:.1f} | {r['frame_ms']:.1f} | "
              f"{r['evals']:.2f} | {r['primitives']:.1f} + {r['shading_primitives']:.1f} | "
              f"{fmt(r['prepass_ms'], 0)} | {fmt(r['leaves_per_cell'], 1)} | {fmt(r['buffers_mib'], 1)} | {r['first_frame_s']:.1f} |")


if __name__ == "__main__":
    main()
