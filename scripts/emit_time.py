"""Times `sdfc emit` of a 10 001-node scene as a whole process (median of 25 runs, after one
untimed run), the scene being the one compiler/benches/compile.rs generates for 1 000 groups.
Usage: python3 scripts/emit_time.py path/to/sdfc > emit-process.json"""
import json
import os
import subprocess
import sys
import tempfile
import time

sdfc = sys.argv[1]
groups = 1000
src = "camera { eye (0, 4, -12) target (0, 0, 0) }\nunion {\n"
for g in range(groups):
    x, z = (g % 32) * 0.7, (g // 32) * 0.7
    src += (f"  smooth_union(0.1) {{\n    sphere(0.2) at ({x}, 0.2, {z})\n"
            f"    box(0.3) |> rotate(y, {g}deg) at ({x}, 0.5, {z})\n"
            f"    torus(0.25, 0.05) at ({x}, 0.8, {z})\n"
            f"    cylinder(0.05, 0.6) at ({x}, 0.3, {z})\n  }}\n")
src += "}\n"
with tempfile.TemporaryDirectory() as d:
    scene = os.path.join(d, "nodes.sdf")
    open(scene, "w").write(src)
    nodes = subprocess.run([sdfc, "check", scene], capture_output=True, text=True).stdout
    nodes = int(next(l.split(":")[1] for l in nodes.splitlines() if "nodes:" in l))
    times = {}
    for target in ["wgsl", "spirv"]:
        cmd = [sdfc, "emit", scene, "--target", target, "-q", "-o", os.path.join(d, "out")]
        subprocess.run(cmd, check=True)
        runs = []
        for _ in range(25):
            t = time.perf_counter()
            subprocess.run(cmd, check=True)
            runs.append(time.perf_counter() - t)
        runs.sort()
        times[target] = runs[len(runs) // 2]
print(json.dumps({"nodes": nodes, "bytes": len(src), "seconds": times}, indent=2))
