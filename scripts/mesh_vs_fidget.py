#!/usr/bin/env python3
"""`sdfc mesh` side by side with fidget's mesher (Manifold Dual Contouring, JIT, all cores) on
the same five shapes in [-1, 1]³ at 16 to 256 cells a side, as issue 35 asks: time to mesh
(sdfc: up to its "measuring" step, materials included; fidget: Octree::build and walk_dual),
triangles, and the largest distance to the exact surface of the vertices and of the
triangles' centroids (sdfc also at the resolutions between, a quarter of an octave apart from
8 cells, so that equal error is matched by the coarsest sdfc grid that reaches it), both tools' meshes measured by the same exact distance functions in f64
(here for sdfc's STL, clipped to the box as sdfc caps the cut, in the harness for fidget's). Best of 3. Prints two markdown tables: every
run, and each fidget run against the fastest sdfc run whose error is no larger (equal error).

With LIBFIVE_MESH set to a built `bench/libfive-mesh` harness (libfive's dual contouring,
built by hand: bench/libfive-mesh/README.md), libfive's runs are added: a column group in the
first table and a third table, each libfive run against the fastest sdfc run of no larger error.

Usage: mesh_vs_fidget.py SDFC   (builds bench/fidget-mesh with cargo first; needs numpy)
"""
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HARNESS = os.path.join(ROOT, "bench", "fidget-mesh")
SCENES = {
    "ball": "sphere(0.8)",
    "turned box": "box((1.6, 0.96, 1.28)) |> rotate(y, 30deg) |> rotate(x, 20deg)",
    "whole turned box": "box((1.4, 0.84, 1.12)) |> rotate(y, 30deg) |> rotate(x, 20deg)",
    "box less a ball": "subtract { box(1.6) sphere(0.48) }",
    "torus": "torus(0.72, 0.24)",
}


BOX = np.array([0.8, 0.48, 0.64])
A, B = np.radians(30.0), np.radians(20.0)


def box_exact(p, b):
    q = np.abs(p) - b
    return np.linalg.norm(np.maximum(q, 0.0), axis=1) + np.minimum(q.max(axis=1), 0.0)


def unturn(p, a, b):
    """The harness's `unturn`: undo the rotation about x by b, then about y by a."""
    s, c = np.sin(-b), np.cos(-b)
    q = np.stack([p[:, 0], c * p[:, 1] - s * p[:, 2], s * p[:, 1] + c * p[:, 2]], axis=1)
    s, c = np.sin(-a), np.cos(-a)
    return np.stack([c * q[:, 0] + s * q[:, 2], q[:, 1], -s * q[:, 0] + c * q[:, 2]], axis=1)


def torus(p):
    q = np.hypot(p[:, 0], p[:, 2]) - 0.72
    return np.hypot(q, p[:, 1]) - 0.24


EXACT = {
    "ball": lambda p: np.linalg.norm(p, axis=1) - 0.8,
    "turned box": lambda p: box_exact(unturn(p, A, B), BOX),
    "whole turned box": lambda p: box_exact(unturn(p, A, B), np.array([0.7, 0.42, 0.56])),
    "box less a ball": lambda p: np.maximum(box_exact(p, 0.8), -(np.linalg.norm(p, axis=1) - 0.48)),
    "torus": torus,
}


def stl_triangles(path):
    """A binary STL's triangles as an (n, 3, 3) array of f64."""
    raw = open(path, "rb").read()
    n = int.from_bytes(raw[80:84], "little")
    rec = np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    return np.frombuffer(raw, dtype=rec, count=n, offset=84)["v"].astype(np.float64)


def sdfc_run(sdfc, name, scene, res):
    with tempfile.TemporaryDirectory() as d:
        src = os.path.join(d, "s.sdf")
        stl = os.path.join(d, "m.stl")
        open(src, "w").write(scene + "\n")
        best = None
        for _ in range(3):
            out = subprocess.run(
                [sdfc, "mesh", src, "-o", stl, "--cell", repr(2.0 / res),
                 "--bounds=-1,-1,-1,1,1,1", "--stats"], capture_output=True, text=True)
            if out.returncode:
                sys.exit(out.stderr)
            t = float(re.search(r"([0-9.]+) s  measuring", out.stderr).group(1))
            best = t if best is None else min(best, t)
        tris = stl_triangles(stl)
    # sdfc caps what the box [-1, 1]³ cuts (the turned box reaches past it):
    # measured against the shape clipped to the box, as sdfc meshes it (fidget's mesh stops
    # open at the box; its points inside lie on the shape itself).
    f = lambda p: np.maximum(EXACT[name](p), box_exact(p, 1.0))
    vertex = np.abs(f(tris.reshape(-1, 3))).max()
    face = np.abs(f(tris.mean(axis=1))).max()
    return best, len(tris), vertex, face


def other(exe, depth):
    """One harness's lines at `depth` (best of 3), by shape: (time, triangles, vertices ≤,
    centroids ≤)."""
    lines = subprocess.run([exe, str(depth), "3"], capture_output=True, text=True,
                           check=True).stdout.splitlines()
    out = {}
    for l in lines:
        f = l.split("\t")
        out[f[0]] = (float(f[1]), int(f[2]), float(f[4]), float(f[6]))
    return out


def against(rows, tool):
    """Each of `tool`'s runs against the fastest sdfc run whose error is no larger."""
    print(f"| shape | {tool}: cells, time (s), error | sdfc at no larger error: cells, time (s), "
          "error | sdfc faster by |")
    print("| --- | --- | --- | ---: |")
    for name in SCENES:
        for f in [r for r in rows if r[0] == name and r[2] == tool]:
            err = max(f[5], f[6])
            ok = [r for r in rows if r[0] == name and r[2] == "sdfc" and max(r[5], r[6]) <= err]
            if not ok:
                print(f"| {name} | {f[1]}, {f[3]:.3f}, {err:.1e} | none (finest: "
                      f"{min(max(r[5], r[6]) for r in rows if r[0] == name and r[2] == 'sdfc'):.1e})"
                      f" | — |")
                continue
            s = min(ok, key=lambda r: r[3])
            print(f"| {name} | {f[1]}, {f[3]:.3f}, {err:.1e} | {s[1]:.3g}, {s[3]:.3f}, "
                  f"{max(s[5], s[6]):.1e} | {f[3] / max(s[3], 1e-3):.1f}× |")
    print()


def main():
    sdfc = sys.argv[1]
    subprocess.run(["cargo", "build", "--release", "--quiet"], cwd=HARNESS, check=True)
    tools = {"fidget": os.path.join(HARNESS, "target", "release", "fidget-mesh-harness")}
    if os.environ.get("LIBFIVE_MESH"):
        tools["libfive"] = os.environ["LIBFIVE_MESH"]
    rows = []
    for depth in [4, 5, 6, 7, 8]:
        res = 2 ** depth
        got = {tool: other(exe, depth) for tool, exe in tools.items()}
        for name in SCENES:
            for tool in tools:
                rows.append((name, res, tool) + got[tool][name])
    # sdfc's resolutions need not be powers of two (fidget's octree's are; libfive's here
    # are kept so): a quarter of an octave apart from 8 to 256 cells, so that "at no larger
    # error" finds the coarsest sdfc grid that is as exact, not the next power of two.
    for name, scene in SCENES.items():
        for k in range(12, 33):
            res = 2 ** (k / 4)
            t, tris, vertex, face = sdfc_run(sdfc, name, scene, res)
            rows.append((name, res, "sdfc", t, tris, vertex, face))
    head = "| shape | cells a side | sdfc: time (s) | triangles | vertices ≤ | centroids ≤ |"
    for tool in tools:
        head += f" {tool}: time (s) | triangles | vertices ≤ | centroids ≤ |"
    print(head)
    print("| --- | ---: |" + " ---: |" * (4 * (1 + len(tools))))
    for name in SCENES:
        for res in [16, 32, 64, 128, 256]:
            line = f"| {name} | {res} |"
            for tool in ["sdfc"] + list(tools):
                r = next(r for r in rows if r[:3] == (name, res, tool))
                line += f" {r[3]:.3f} | {r[4]:,} | {r[5]:.1e} | {r[6]:.1e} |"
            print(line)
    print()
    print("| shape | sdfc: cells a side | time (s) | triangles | vertices ≤ | centroids ≤ |")
    print("| --- | ---: | ---: | ---: | ---: | ---: |")
    for r in rows:
        if r[2] == "sdfc" and r[1] not in (16, 32, 64, 128, 256):
            print(f"| {r[0]} | {r[1]:.3g} | {r[3]:.3f} | {r[4]:,} | {r[5]:.1e} | {r[6]:.1e} |")
    print()
    for tool in tools:
        against(rows, tool)


if __name__ == "__main__":
    main()
