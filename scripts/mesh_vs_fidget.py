#!/usr/bin/env python3
"""`sdfc mesh` side by side with fidget's mesher (Manifold Dual Contouring, JIT, all cores) on
the same four shapes in [-1, 1]³ at equal resolution (2^depth cells a side), as issue 35 asks:
time to mesh (sdfc: up to its "measuring" step, materials included; fidget: Octree::build and
walk_dual), triangles, and the vertices' largest distance to the exact surface (sdfc: its own
measure; fidget: the harness's exact distance functions). Best of 3. Prints a markdown table.

Usage: mesh_vs_fidget.py SDFC   (builds bench/fidget-mesh with cargo first)
"""
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HARNESS = os.path.join(ROOT, "bench", "fidget-mesh")
SCENES = {
    "ball": "sphere(0.8)",
    "turned box": "box((1.6, 0.96, 1.28)) |> rotate(y, 30deg) |> rotate(x, 20deg)",
    "box less a ball": "subtract { box(1.6) sphere(0.48) }",
    "torus": "torus(0.8, 0.24)",
}


def sdfc_run(sdfc, scene, res):
    with tempfile.TemporaryDirectory() as d:
        src = os.path.join(d, "s.sdf")
        open(src, "w").write(scene + "\n")
        best = None
        for _ in range(3):
            out = subprocess.run(
                [sdfc, "mesh", src, "-o", os.path.join(d, "m.stl"), "--resolution", str(res),
                 "--bounds=-1,-1,-1,1,1,1", "--stats"], capture_output=True, text=True)
            if out.returncode:
                sys.exit(out.stderr)
            t = float(re.search(r"([0-9.]+) s  measuring", out.stderr).group(1))
            best = t if best is None else min(best, t)
        said = out.stderr
    return (best, int(re.search(r"— (\d+) triangles", said).group(1)),
            float(re.search(r"vertices ≤ ([0-9.e+-]+)", said).group(1)))


def main():
    sdfc = sys.argv[1]
    subprocess.run(["cargo", "build", "--release", "--quiet"], cwd=HARNESS, check=True)
    exe = os.path.join(HARNESS, "target", "release", "fidget-mesh-harness")
    print("| shape | cells a side | sdfc: time (s) | triangles | vertices ≤ | "
          "fidget: time (s) | triangles | vertices ≤ |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for depth in [5, 6, 7, 8]:
        res = 2 ** depth
        lines = subprocess.run([exe, str(depth), "3"], capture_output=True, text=True,
                               check=True).stdout.splitlines()
        fid = {l.split("\t")[0]: l.split("\t")[1:] for l in lines}
        for name, scene in SCENES.items():
            t, tris, err = sdfc_run(sdfc, scene, res)
            f = fid[name]
            print(f"| {name} | {res} | {t:.2f} | {tris:,} | {err:.1e} | {float(f[0]):.2f} | "
                  f"{int(f[1]):,} | {float(f[3]):.1e} |", flush=True)


if __name__ == "__main__":
    main()
