#!/usr/bin/env python3
"""Converts a scene of Barbier, Sanchez et al.'s *Lipschitz Pruning* (Eurographics 2025; their
repository wbrbr/LipschitzPruning, `scenes/*.json`) into an `.sdf` file, for issue 33's
benchmarks on the paper's own scenes.

Usage: scripts/lipschitz_scenes.py SCENE.json [-o OUT.sdf]

Their format: a binary tree of `binaryOperator` nodes (`blendMode` union, sub or inter;
`blendRadius` k, blended by the same quadratic kernel m²/(4k), m = max(0, k − |a − b|), as
sdfc's smooth operators) over `primitive` nodes (`sphere` radius, `box` full `sides` with
`bevel` corners in xz and `round_x`/`round_y` rounding of the extrusion in y, `cylinder`,
`cone`), each with a `matrix` mapping world points to the primitive's (row-major 3×4). What
this converter does:

- a left-deep chain of one operator with one radius becomes one n-ary fold, folded in the
  same order (so the same field); a radius below 1e-6 is written as the sharp operator;
- a matrix must be a move (the scenes here have no turns or scales; anything else is an
  error): the primitive is placed `at` the opposite of its offset;
- a box whose corners and extrusion are rounded alike becomes `rounded_box(sides, r)`; where
  they differ, r is the smallest (said in a comment: the shape is then not the paper's);
- colours become materials (sRGB as given).
"""

import argparse
import json
import sys

OPS = {"union": ("union", "smooth_union"), "sub": ("subtract", "smooth_subtract"),
       "inter": ("intersect", "smooth_intersect")}


def num(x):
    return f"{x:.5g}"


class Writer:
    def __init__(self):
        self.colors = {}
        self.approximated = 0
        self.count = 0

    def material(self, c):
        key = tuple(min(255, int(v * 255.99)) for v in c)
        if key not in self.colors:
            self.colors[key] = f"m{len(self.colors)}"
        return self.colors[key]

    def primitive(self, n):
        m = n["matrix"]
        linear = [m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10]]
        if any(abs(a - b) > 1e-6 for a, b in zip(linear, [1, 0, 0, 0, 1, 0, 0, 0, 1])):
            sys.exit("error: a primitive is turned or scaled; this converter places moves only")
        at = f"({num(-m[3])}, {num(-m[7])}, {num(-m[11])})"
        kind = n["primitiveType"]
        self.count += 1
        if kind == "sphere":
            shape = f"sphere({num(n['radius'])})"
        elif kind == "box":
            sx, sy, sz = n["sides"]
            # Their corner radius: the bevel, stored in 8 bits of max(sx, sz), halved.
            top = max(sx, sz)
            corners = [int(b * 255 / top) * top / 255 / 2 for b in n["bevel"]]
            rounding = [n["round_x"], n["round_y"]]
            r = min(corners + rounding + [sx / 2, sy / 2, sz / 2])
            if max(corners + rounding) - r > 1e-4:
                self.approximated += 1
            shape = (f"rounded_box(({num(sx)}, {num(sy)}, {num(sz)}), {num(r)})" if r > 0
                     else f"box(({num(sx)}, {num(sy)}, {num(sz)}))")
        elif kind == "cylinder":
            shape = f"cylinder({num(n['radius'])}, {num(n['height'])})"
        else:
            sys.exit(f"error: no conversion for a `{kind}` yet")
        return f"{shape} at {at} : {self.material(n['color'])}"

    def node(self, n, indent):
        pad = "  " * indent
        if n["nodeType"] == "primitive":
            return [pad + self.primitive(n)]
        mode, k = n["blendMode"], n["blendRadius"]
        # The left-deep chain of this operator and radius, in folding order.
        chain = []
        x = n
        while x["nodeType"] == "binaryOperator" and x["blendMode"] == mode and x["blendRadius"] == k:
            chain.append(x["rightChild"])
            x = x["leftChild"]
        chain.append(x)
        chain.reverse()
        hard, smooth = OPS[mode]
        # (A radius below a millionth — the trees' root has 1e-8 — blends nothing at float
        # precision: written as the sharp operator.)
        head = f"{smooth}({num(k)})" if k > 1e-6 else hard
        lines = [f"{pad}{head} {{"]
        for c in chain:
            lines += self.node(c, indent + 1)
        return lines + [f"{pad}}}"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("-o", "--output")
    a = ap.parse_args()
    sys.setrecursionlimit(100000)
    with open(a.scene) as f:
        d = json.load(f)
    w = Writer()
    body = w.node(d, 0)
    lo, hi = d["aabb_min"], d["aabb_max"]
    c = [(l + h) / 2 for l, h in zip(lo, hi)]
    size = max(h - l for l, h in zip(lo, hi))
    eye = (c[0] + 0.35 * size, c[1] + 0.45 * size, c[2] - 1.5 * size)
    head = [
        f"// {a.scene.split('/')[-1]} of Barbier, Sanchez et al. 2025 (wbrbr/LipschitzPruning),",
        f"// converted by scripts/lipschitz_scenes.py: {w.count} primitives"
        + (f", {w.approximated} boxes rounded by their smallest radius" if w.approximated else ""),
        f"camera {{ eye ({num(eye[0])}, {num(eye[1])}, {num(eye[2])})  target ({num(c[0])}, {num(c[1])}, {num(c[2])}) }}",
        "light { direction (-0.4, 1, -0.5) }",
    ]
    for rgb, name in w.colors.items():
        head.append(f"material {name} {{ color #{rgb[0]:02x}{rgb[1]:02x}{rgb[2]:02x} }}")
    text = "\n".join(head + body) + "\n"
    if a.output:
        with open(a.output, "w") as f:
            f.write(text)
    else:
        sys.stdout.write(text)


if __name__ == "__main__":
    main()
