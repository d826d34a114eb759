#!/usr/bin/env python3
"""Measures what the GPU driver's compile of a scene costs against the shader's inlined size.

Usage: scripts/compile_cost.py SDFC OUT_DIR [--backend vulkan|gl] [--max-size N] [--quick | --held-out]

Writes a corpus of generated scenes (flat and smooth unions, materials, shared `let`s, long
implicit expressions, transforms) and copies of the examples into OUT_DIR, then for each: its
inlined size (`sdfc check`'s "shader size"), and the wall time and peak memory of a 16×9
`sdfc render` with Mesa's shader cache off (`MESA_SHADER_CACHE_DISABLE=true`), the device
opening of a trivial scene subtracted. Prints one CSV row per scene, then the least-squares fit
of log(time) and log(memory) against log(size) — the model in docs/stability.md.
"""

import json
import math
import os
import random
import shutil
import subprocess
import sys
import tempfile

HEAD = """camera { eye (0, 3, -9)  target (0, 0, 0) }
light { direction (-0.4, 1, -0.5) }
"""


def spheres(n, smooth, rng):
    parts = []
    for _ in range(n):
        x, y, z = (rng.uniform(-3, 3) for _ in range(3))
        parts.append(f"  sphere({rng.uniform(0.05, 0.3):.3f}) at ({x:.3f}, {y:.3f}, {z:.3f})")
    op = "smooth_union(0.1)" if smooth else "union"
    return HEAD + op + " {\n" + "\n".join(parts) + "\n}\n"


def boxes(n, rng):
    mats = "".join(
        f"material m{i} {{ color ({rng.random():.2f}, {rng.random():.2f}, {rng.random():.2f}) }}\n"
        for i in range(8)
    )
    parts = []
    for i in range(n):
        x, y, z = (rng.uniform(-3, 3) for _ in range(3))
        parts.append(
            f"  rotate((0, 1, 0), {rng.uniform(0, 90):.1f}deg) {{ rounded_box(({rng.uniform(0.1, 0.4):.2f}, 0.2, 0.3), 0.02) }} at ({x:.3f}, {y:.3f}, {z:.3f}) : m{i % 8}"
        )
    return HEAD + mats + "union {\n" + "\n".join(parts) + "\n}\n"


def shared(levels):
    text = HEAD + "let s0 = torus(0.3, 0.1)\n"
    for i in range(1, levels + 1):
        d = 0.5 * 0.8**i
        text += f"let s{i} = union {{ s{i-1} at ({d:.4f}, 0, 0)  s{i-1} at (0, {d:.4f}, {-d:.4f}) }}\n"
    return text + f"s{levels}\n"


def implicit(terms, rng):
    ks = [(rng.uniform(0.5, 3), rng.uniform(0.5, 3)) for _ in range(terms)]
    body = " + ".join(f"sin(x * {a:.2f} + z * {b:.2f})" for a, b in ks)
    lam = 1 + 0.05 * sum(math.hypot(a, b) for a, b in ks)
    return HEAD + f"implicit {{ y - 0.05 * ({body}) }} @lipschitz({lam:.2f})\n"


def mixed(n, rng):
    kinds = ["torus(0.3, 0.08)", "cylinder(0.2, 0.5)", "octahedron(0.3)", "capsule(0.4, 0.1)", "cone(0.3, 0.5, 0.1)"]
    parts = []
    for _ in range(n):
        x, y, z = (rng.uniform(-3, 3) for _ in range(3))
        k = rng.choice(kinds)
        parts.append(f"  twist(0.5) {{ {k} }} at ({x:.3f}, {y:.3f}, {z:.3f})")
    return HEAD + "smooth_union(0.05) {\n" + "\n".join(parts) + "\n}\n"


def materials(n, rng):
    mats = "".join(
        f"material m{i} {{ color ({rng.random():.2f}, {rng.random():.2f}, {rng.random():.2f}) }}\n"
        for i in range(n)
    )
    parts = []
    for i in range(n):
        x, y, z = (rng.uniform(-3, 3) for _ in range(3))
        parts.append(f"  sphere({rng.uniform(0.05, 0.2):.3f}) at ({x:.3f}, {y:.3f}, {z:.3f}) : m{i}")
    return HEAD + mats + "union {\n" + "\n".join(parts) + "\n}\n"


def written(out, scenes):
    """Writes each scene to OUT; its runs: as written, and without box trees where it has them."""
    runs = []
    for name, text in scenes.items():
        path = os.path.join(out, name + ".sdf")
        with open(path, "w") as f:
            f.write(text)
        runs.append((path, []))
        if name.startswith(("union", "boxes", "materials")):
            runs.append((path, ["--no-bvh"]))
    return runs


def held_out(out):
    """Scenes the fit never saw: other sizes, a second seed, one material per part."""
    rng = random.Random(2)
    scenes = {
        "union_384": spheres(384, False, rng),
        "union_768": spheres(768, False, rng),
        "smooth_384": spheres(384, True, rng),
        "boxes_materials_128": boxes(128, rng),
        "twisted_128": mixed(128, rng),
        "shared_lets_9": shared(9),
        "implicit_150": implicit(150, rng),
        "materials_256": materials(256, rng),
        "materials_1000": materials(1000, rng),
    }
    return written(out, scenes)


def corpus(out, quick, examples):
    rng = random.Random(1)
    scenes = {}
    sizes = [16, 128, 512, 1024] if quick else [16, 64, 256, 512, 1024, 1536, 2048]
    for n in sizes:
        scenes[f"union_{n}"] = spheres(n, False, rng)
    for n in sizes[:-1]:
        scenes[f"smooth_{n}"] = spheres(n, True, rng)
    for n in sizes[:-2]:
        scenes[f"boxes_materials_{n}"] = boxes(n, rng)
        scenes[f"twisted_{n}"] = mixed(n, rng)
    for levels in [4, 8, 10] if quick else [4, 6, 8, 10, 12]:
        scenes[f"shared_lets_{levels}"] = shared(levels)
    for terms in [8, 64] if quick else [8, 32, 96, 192]:
        scenes[f"implicit_{terms}"] = implicit(terms, rng)
    runs = written(out, scenes)
    for e in sorted(os.listdir(examples)):
        if e.endswith(".sdf"):
            runs.append((shutil.copy(os.path.join(examples, e), out), []))
    return runs


def cost_of(sdfc, path, flags):
    """The manifest's `compile` section for the module `render` compiles, or None if refused."""
    with tempfile.TemporaryDirectory() as tmp:
        shader, manifest = os.path.join(tmp, "s.wgsl"), os.path.join(tmp, "m.json")
        cmd = [sdfc, "emit", path, "--target", "wgsl", "--entry", "compute", "-o", shader,
               "--manifest", manifest]
        if subprocess.run(cmd + flags, capture_output=True).returncode != 0:
            print(f"# {path}: refused by `emit`", file=sys.stderr)
            return None
        with open(manifest) as f:
            return json.load(f)["compile"]


def measure(sdfc, path, backend, flags):
    """(seconds, peak MB) of a 16×9 render."""
    env = dict(os.environ, MESA_SHADER_CACHE_DISABLE="true")
    with tempfile.TemporaryDirectory() as tmp:
        cmd = ["/usr/bin/time", "-f", "%e %M", sdfc, "render", path, "--size", "16x9",
               "--backend", backend, "--allow-slow-compile", "-o", os.path.join(tmp, "x.png")]
        r = subprocess.run(cmd + flags, capture_output=True, text=True, env=env)
    lines = r.stderr.strip().splitlines()
    seconds, kb = lines[-1].split()
    if r.returncode != 0:
        raise SystemExit(f"render of {path} failed:\n{r.stderr}")
    return float(seconds), int(kb) / 1024


def fit(rows):
    """The model of sdfc_compiler::cost::predict fitted to rows of (cost, seconds): least squares
    of the relative error, seconds = a·squares + b·chains + c·branches² + d·transcendental²."""
    import numpy as np

    x = np.array([[c["squares"], c["chains"], c["branches"] ** 2, c["transcendental"] ** 2]
                  for c, _, _ in rows], dtype=float)
    t = np.array([s for _, s, _ in rows])
    coef, *_ = np.linalg.lstsq(x / t[:, None], np.ones_like(t), rcond=None)
    ratios = t / (x @ coef)
    return coef, ratios.min(), ratios.max()


def main():
    args = sys.argv[1:]
    if len(args) < 2:
        raise SystemExit(__doc__)
    sdfc, out = args[0], args[1]
    backend = args[args.index("--backend") + 1] if "--backend" in args else "vulkan"
    max_size = int(args[args.index("--max-size") + 1]) if "--max-size" in args else 10**9
    os.makedirs(out, exist_ok=True)
    examples = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples")
    if "--held-out" in args:
        runs = held_out(out)
    else:
        runs = corpus(out, "--quick" in args, examples)
    trivial = os.path.join(out, "trivial.sdf")
    with open(trivial, "w") as f:
        f.write(HEAD + "sphere(1)\n")
    base, base_mb = measure(sdfc, trivial, backend, [])
    print(f"# {backend}: a trivial scene's render {base:.2f} s, {base_mb:.0f} MB (subtracted from time)")
    print("scene,size,calls,branches,transcendental,squares,chains,predicted,seconds,compile_seconds,peak_mb")
    rows = []
    for p, flags in runs:
        c = cost_of(sdfc, p, flags)
        if c is None or c["inlined_size"] > max_size:
            continue
        seconds, mb = measure(sdfc, p, backend, flags)
        compile_s = max(seconds - base, 0.01)
        rows.append((c, compile_s, mb))
        name = os.path.basename(p) + "".join(" " + f for f in flags)
        counts = ",".join(str(c[k]) for k in ["inlined_size", "calls", "branches", "transcendental", "squares", "chains"])
        print(f"{name},{counts},{c['predicted_seconds']:.2f},{seconds:.2f},{compile_s:.2f},{mb:.0f}", flush=True)
    timed = [r for r in rows if r[1] >= 0.2]
    if timed:
        ratios = [t / c["predicted_seconds"] for c, t, _ in timed]
        print(f"# measured/predicted over {len(timed)} scenes that took >= 0.2 s: {min(ratios):.2f} to {max(ratios):.2f}")
        if "--held-out" not in args:
            coef, lo, hi = fit(timed)
            print("# refitted: seconds = " + " + ".join(f"{c:.3g}·{n}" for c, n in zip(coef, ["squares", "chains", "branches²", "transcendental²"])) + f"; measured/fitted {lo:.2f} to {hi:.2f}")
    print(f"# peak memory at most {max(r[2] for r in rows):.0f} MB")


if __name__ == "__main__":
    main()
