#!/usr/bin/env python3
"""Measures `sdfc mesh`: time, triangles, field evaluations and the distance to the surface,
for shapes with corners and curved ones, at doubling resolutions, pruned by the bound against
every cell (the brute-force grid), sharp against plain. Prints a markdown table.

Usage: mesh_bench.py SDFC [--repeat N] [--max-brute N]
Times are the fastest of N runs (this machine's timings vary run to run).
"""
import argparse
import os
import re
import subprocess
import tempfile
import time

SHAPES = {
    "ball": "sphere(1)",
    "turned box": "box((1, 0.6, 0.8)) |> rotate(y, 30deg) |> rotate(x, 20deg)",
    "box less a ball": "subtract { box(1) sphere(0.6) }",
    "torus": "torus(1, 0.3) |> rotate(x, 30deg)",
    "mandelbulb": "mandelbulb(power = 8, iterations = 8)",
}


def run(sdfc, scene, resolution, extra, repeat):
    with tempfile.TemporaryDirectory() as d:
        src = os.path.join(d, "s.sdf")
        with open(src, "w") as f:
            f.write(scene + "\n")
        best = None
        for _ in range(repeat):
            start = time.perf_counter()
            out = subprocess.run(
                [sdfc, "mesh", src, "-o", os.path.join(d, "m.stl"), "--resolution",
                 str(resolution), "--stats", *extra],
                capture_output=True, text=True)
            took = time.perf_counter() - start
            if out.returncode != 0:
                raise SystemExit(out.stderr)
            best = took if best is None else min(best, took)
        said = out.stderr
    num = lambda pat: float(re.search(pat, said).group(1))
    return {
        "seconds": best,
        "triangles": int(num(r"— (\d+) triangles")),
        "evaluations": int(num(r"(\d+) field evaluations")),
        "vertex": num(r"vertices ≤ ([0-9.e+-]+)"),
        "face": num(r"faces ≤ ([0-9.e+-]+)"),
        "closed": "closed, 2-manifold" in said,
    }


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("sdfc")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--max-brute", type=int, default=128)
    a = ap.parse_args()
    print("| shape | cells a side | method | time (s) | triangles | field evaluations | "
          "vertices ≤ | faces ≤ | brute force: time (s), evaluations, mesh | closed |")
    print("| --- | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | --- |")
    for name, scene in SHAPES.items():
        for res in [32, 64, 128, 256]:
            if name == "mandelbulb" and res > 128:
                continue  # (its 256 takes minutes a run on this machine's two cores)
            for method in ["sharp", "plain"]:
                r = run(a.sdfc, scene, res, ["--method", method], a.repeat)
                brute = ""
                if method == "sharp" and res <= a.max_brute:
                    b = run(a.sdfc, scene, res, ["--method", method, "--no-prune"], 1)
                    # The same mesh where the bound holds; a fractal's estimate is not a bound,
                    # and the brute force finds islands the pruning dropped.
                    same = "same mesh" if b["triangles"] == r["triangles"] else \
                        f"{b['triangles'] - r['triangles']:+,} triangles"
                    brute = f"{b['seconds']:.2f}, {b['evaluations']:,}, {same}"
                print(f"| {name} | {res} | {method} | {r['seconds']:.2f} | {r['triangles']:,} | "
                      f"{r['evaluations']:,} | {r['vertex']:.1e} | {r['face']:.1e} | {brute} | "
                      f"{'yes' if r['closed'] else 'NO'} |", flush=True)


if __name__ == "__main__":
    main()
