#!/usr/bin/env python3
"""Writes a union of N spheres in the unit box, for the large-scene benchmarks (issue 33).

Usage: scripts/spheres.py N smooth|hard [--seed S] [-o OUT.sdf]

The spheres' centres are uniform in [-1, 1]³ (a fixed sequence per seed); their radii are
molecule-like — between 0.7 and 1.3 of a common radius that shrinks as N^(-1/3), so the
spheres fill about the same share of the box at every N (about a sixth). A smooth union
blends with k = 0.4 of the common radius. The camera looks at the box from the front.
"""

import argparse
import random
import sys


def scene(n, smooth, seed):
    rng = random.Random(seed)
    r0 = 0.55 * n ** (-1.0 / 3.0)
    head = [
        f"// {n} spheres in the unit box, {'smoothly blended' if smooth else 'hard union'}",
        f"// (scripts/spheres.py {n} {'smooth' if smooth else 'hard'} --seed {seed})",
        "camera { eye (0.6, 0.8, -3.2)  target (0, 0, 0) }",
        "light { direction (-0.4, 1, -0.5) }",
        "material ink { color #4a78c8 }",
    ]
    op = f"smooth_union({0.4 * r0:.4f})" if smooth else "union"
    parts = []
    for _ in range(n):
        x, y, z = (rng.uniform(-1, 1) for _ in range(3))
        r = r0 * rng.uniform(0.7, 1.3)
        parts.append(f"  sphere({r:.4f}) at ({x:.4f}, {y:.4f}, {z:.4f})")
    return "\n".join(head) + f"\n{op} {{\n" + "\n".join(parts) + "\n} : ink\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("n", type=int)
    ap.add_argument("way", choices=["smooth", "hard"])
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("-o", "--output")
    a = ap.parse_args()
    text = scene(a.n, a.way == "smooth", a.seed)
    if a.output:
        with open(a.output, "w") as f:
            f.write(text)
    else:
        sys.stdout.write(text)


if __name__ == "__main__":
    main()
