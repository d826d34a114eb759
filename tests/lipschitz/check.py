#!/usr/bin/env python3
"""Checks the Lipschitz annotation corpus in tests/lipschitz/{wrong,right}/*.sdf by hand-free
numerics (plain Python 3, no NumPy).

Every scene's header gives the expected verdict, the true constant to 3 significant digits, the
annotated value and a one-line derivation; below it `// class:`, `// exact:` (the constant as a
Python expression, e.g. `sqrt(2501)`) and `// steep-at:` (a world point where the slope is at its
supremum). This script parses and evaluates the scene with a small f64 interpreter of the sdfc
language (only the subset the corpus uses; each formula restated from compiler/src/catalog) and
checks, for the one annotated node:

  - the file has exactly one `@lipschitz(L)` and L equals the header's `annotated`;
  - the header's true-lipschitz is `exact` to 3 significant digits;
  - sampling |grad f| of the node's raw field (central differences, h = 1e-6) in a cube of half
    size 12 around its local origin, in balls of radius 1 ... 1e-3 around the steep point, then
    hill-climbing from the best samples, never exceeds `exact` (by more than 1e-6 relative) and
    comes within 0.2 % of it (so `exact` is the supremum, not just a bound);
  - |grad f| at the steep point (mapped into the node's frame) is within 0.2 % of `exact`;
  - the steep point is in the camera's view (within fov/2 of the view axis both horizontally
    and vertically), nearer than the trace's max_distance, outside every surface, and the segment
    from the eye to it stays outside every surface, so camera rays reach it;
  - wrong: exact / annotated in [1.05, 10]; right: annotated >= exact, either equal (tight) or
    loose by x1.01 ... x3.

The classes added later take more header lines (README.md, "File format"):

  - ranged (`// worst-at: a = 2; b = 0`): `param`s are evaluated at given values; the node is
    within the annotation at the defaults, reaches `exact` at worst-at, and never exceeds it on a
    grid over the ranges (parameters without a range: default, a+1, a-1, 2a+1, -a, a/2, 10a+3);
  - call (`// worst-call: pair(1.5) > lump(2 * k)`): `fn`s are expanded at each call, one node per
    call; the named call reaches `exact`, no call exceeds it, and (wrong) some call is within the
    annotation, (right) every one;
  - secondary (`// reached-by: shadow | reflection | refraction | camera`, `// via: (x, y, z)`): the
    steep point is outside the camera's 16:9 frustum and on the shadow / reflected / refracted ray
    that leaves the visible surface point `via` (camera: visible, as above).

Usage: python3 tests/lipschitz/check.py [--sdfc target/release/sdfc] [--old OTHER_SDFC] [--table] [FILES...]
With --sdfc it also runs `sdfc check FILE` and `sdfc check --lipschitz FILE` (which must exit 0)
and records whether the annotation verifier warned ("the annotated Lipschitz bound is too small");
--old runs a second build the same way; --table prints the README tables.
"""

import copy
import glob
import math
import os
import random
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))

# ---------------------------------------------------------------------------------------------
# Syntax (grammar/sdf.pest)

TOKEN = re.compile(
    r"""(?P<ws>\s+)|(?P<lc>//[^\n]*)|(?P<bc>/\*.*?\*/)
      |(?P<num>(?:\d+(?:\.(?!\.)\d*)?|\.\d+)(?:[eE][+-]?\d+)?)(?P<unit>[A-Za-z]+)?
      |(?P<color>\#[A-Za-z0-9]*)
      |(?P<id>[A-Za-z_][A-Za-z0-9_]*)
      |(?P<op>\|>|\.\.|[-+*/^(){},;=:@.])""",
    re.X | re.S,
)
KEYWORDS = {
    "let", "param", "fn", "in", "at", "camera", "light", "trace", "material", "bound", "occlusion", "fog",
    "background",
}


def tokenize(src):
    out, i, line = [], 0, 1
    while i < len(src):
        m = TOKEN.match(src, i)
        if not m:
            raise SyntaxError(f"line {line}: bad character {src[i]!r}")
        kind = m.lastgroup
        if kind == "unit":
            kind = "num"
        text = m.group(0)
        # each token: (kind, value, line, start offset, end offset)
        if kind == "num":
            out.append(("num", (float(m.group("num")), m.group("unit")), line, i, m.end()))
        elif kind == "color":
            out.append(("color", text, line, i, m.end()))
        elif kind == "id":
            out.append(("kw" if text in KEYWORDS else "id", text, line, i, m.end()))
        elif kind == "op":
            out.append(("op", text, line, i, m.end()))
        line += text.count("\n")
        i = m.end()
    out.append(("eof", None, line, i, i))
    return out


class Parser:
    def __init__(self, src):
        self.src = src
        self.t = tokenize(src)
        self.i = 0

    def peek(self, k=0):
        return self.t[self.i + k]

    def take(self):
        tok = self.t[self.i]
        self.i += 1
        return tok

    def is_op(self, s, k=0):
        tok = self.peek(k)
        return tok[0] == "op" and tok[1] == s

    def expect(self, s):
        tok = self.take()
        if tok[1] != s:
            raise SyntaxError(f"line {tok[2]}: expected {s!r}, found {tok[1]!r}")
        return tok

    def file(self):
        stmts = []
        while self.peek()[0] != "eof":
            tok = self.peek()
            if tok[0] == "kw" and tok[1] == "let":
                self.take()
                name = self.take()[1]
                self.expect("=")
                stmts.append(("let", name, self.expr()))
            elif tok[0] == "kw" and tok[1] == "param":
                # param NAME = DEFAULT [in LOW..HIGH]
                self.take()
                name = self.take()[1]
                self.expect("=")
                default, lo, hi = self.expr(), None, None
                if self.peek()[0] == "kw" and self.peek()[1] == "in":
                    self.take()
                    lo = self.expr()
                    self.expect("..")
                    hi = self.expr()
                stmts.append(("param", name, default, lo, hi))
            elif tok[0] == "kw" and tok[1] == "fn":
                # fn NAME(p, p: type, p = default, p: type = default) = BODY
                self.take()
                name = self.take()[1]
                self.expect("(")
                params = []
                while not self.is_op(")"):
                    pname, default = self.take()[1], None
                    if self.is_op(":"):
                        self.take()
                        self.take()
                    if self.is_op("="):
                        self.take()
                        default = self.expr()
                    params.append((pname, default))
                    if self.is_op(","):
                        self.take()
                self.take()
                self.expect("=")
                stmts.append(("fn", name, params, self.expr()))
            elif tok[0] == "kw" and tok[1] in ("camera", "light", "trace", "material", "bound", "occlusion", "fog"):
                self.take()
                kind = self.take()[1] if self.peek()[0] == "id" else None
                settings = {}
                if self.is_op("{"):
                    self.take()
                    while not self.is_op("}"):
                        key = self.take()[1]
                        settings[key] = self.expr()
                        if self.is_op(";") or self.is_op(","):
                            self.take()
                    self.take()
                stmts.append(("block", tok[1], kind, settings))
            elif tok[0] == "kw" and tok[1] == "background":
                self.take()
                stmts.append(("background", self.expr()))
            else:
                stmts.append(("expr", self.expr()))
            if self.is_op(";"):
                self.take()
        return stmts

    # + - < * / < unary - < ^ < postfix
    def expr(self):
        e = self.product()
        while self.is_op("+") or self.is_op("-"):
            op = self.take()[1]
            e = ("bin", op, e, self.product())
        return e

    def product(self):
        e = self.unary()
        while self.is_op("*") or self.is_op("/"):
            op = self.take()[1]
            e = ("bin", op, e, self.unary())
        return e

    def unary(self):
        if self.is_op("-"):
            self.take()
            return ("neg", self.unary())
        e = self.postfix()
        if self.is_op("^"):
            self.take()
            e = ("bin", "^", e, self.unary())
        return e

    def postfix(self):
        e = self.primary()
        while True:
            tok = self.peek()
            if self.is_op("|>"):
                self.take()
                e = ("pipe", e, self.primary())
            elif self.is_op(":"):
                self.take()
                e = ("tag", e, self.take()[1])
            elif self.is_op("@"):
                self.take()
                name = self.take()[1]
                e = ("annot", e, name, self.args(), tok[2], tok[3])
            elif self.is_op("."):
                self.take()
                e = ("comp", e, self.take()[1])
            elif tok[0] == "kw" and tok[1] == "at":
                self.take()
                e = ("at", e, self.primary())
            else:
                return e

    def args(self):
        self.expect("(")
        out = []
        while not self.is_op(")"):
            key = None
            if self.peek()[0] == "id" and self.is_op("=", 1):
                key = self.take()[1]
                self.take()
            out.append((key, self.expr()))
            if self.is_op(","):
                self.take()
        self.take()
        return out

    def primary(self):
        tok = self.take()
        kind, val, line = tok[:3]
        if kind == "op" and val == "(":
            first = self.expr()
            if self.is_op(","):
                self.take()
                second = self.expr()
                self.expect(",")
                third = self.expr()
                if self.is_op(","):
                    self.take()
                self.expect(")")
                return ("vec", first, second, third)
            self.expect(")")
            return first
        if kind == "num":
            return ("num", val[0], val[1])
        if kind == "color":
            return ("color", val)
        if kind == "id":
            args = self.args() if self.is_op("(") else None
            text = self.src[tok[3] : self.t[self.i - 1][4]]  # the call as written (without a block)
            block = None
            if self.is_op("{"):
                self.take()
                block = []
                while not self.is_op("}"):
                    block.append(self.expr())
                    if self.is_op(";") or self.is_op(","):
                        self.take()
                self.take()
            if args is None and block is None:
                return ("name", val)
            return ("call", val, args or [], block, line, text)
        raise SyntaxError(f"line {line}: unexpected {val!r}")


# ---------------------------------------------------------------------------------------------
# Vectors


def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def mul(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a):
    return math.sqrt(dot(a, a))


def unit(a):
    return mul(a, 1.0 / norm(a))


def rotate(v, axis, angle):
    """Rodrigues' rotation, as catalog/geometry.rs `rotate`."""
    s, c = math.sin(angle), math.cos(angle)
    return add(add(mul(v, c), mul(cross(axis, v), s)), mul(axis, dot(axis, v) * (1 - c)))


# ---------------------------------------------------------------------------------------------
# Fields of `implicit` bodies, compiled to Python


def _length(a, b, c):
    return math.sqrt(a * a + b * b + c * c)


def _sqrt(a):
    return math.sqrt(a) if a >= 0 else float("nan")


def _log(a):
    return math.log(a) if a > 0 else (float("-inf") if a == 0 else float("nan"))


def _clamp(a, lo, hi):
    return min(max(a, lo), hi)


MATH = {
    "clamp": _clamp,
    "abs": abs,
    "sqrt": _sqrt,
    "sin": math.sin,
    "cos": math.cos,
    "exp": math.exp,
    "log": _log,
    "min": min,
    "max": max,
    "length": _length,
    "atan2": math.atan2,
}


class Field:
    def __init__(self, code):
        self.code = code


def code_of(v):
    return v.code if isinstance(v, Field) else repr(float(v))


# ---------------------------------------------------------------------------------------------
# Scene nodes: raw field `f`, lambda (after annotation), children and each child's domain map


class Node:
    def __init__(self, kind, f, lam, children=(), maps=None):
        self.kind = kind
        self.f = f
        self.lam = lam
        self.children = list(children)
        self.maps = maps or [lambda p: p] * len(self.children)
        self.annotation = None
        self.line = None


def sd_box(p, b):
    q = (abs(p[0]) - b[0], abs(p[1]) - b[1], abs(p[2]) - b[2])
    return norm((max(q[0], 0), max(q[1], 0), max(q[2], 0))) + min(max(q), 0.0)


def sd_octahedron(p, s):
    p = (abs(p[0]), abs(p[1]), abs(p[2]))
    m = p[0] + p[1] + p[2] - s
    if 3 * p[0] < m:
        q = p
    elif 3 * p[1] < m:
        q = (p[1], p[2], p[0])
    elif 3 * p[2] < m:
        q = (p[2], p[0], p[1])
    else:
        return m / math.sqrt(3)
    k = min(max(0.5 * (q[2] - q[1] + s), 0.0), s)
    return norm((q[0], q[1] - s + k, q[2] - k))


PHI = (1 + math.sqrt(5)) / 2
DODECA = [unit(v) for v in [(0, 1, PHI), (0, -1, PHI), (1, PHI, 0), (-1, PHI, 0), (PHI, 0, 1), (-PHI, 0, 1)]]


def gdf_dodecahedron(p, r, e):
    dots = [abs(dot(p, n)) for n in DODECA]
    if e == 0:
        return max(dots) - r
    m = max(dots)
    if m == 0:
        return -r
    return m * sum((d / m) ** e for d in dots) ** (1 / e) - r


def vec_of(v):
    return v if isinstance(v, tuple) else (float(v),) * 3


# name: (params [(name, default or None)], eval(args, p), lambda(args))
PRIMITIVES = {
    "sphere": ([("radius", 1.0)], lambda a, p: norm(p) - a["radius"], lambda a: 1.0),
    "box": ([("size", 1.0)], lambda a, p: sd_box(p, mul(vec_of(a["size"]), 0.5)), lambda a: 1.0),
    "rounded_box": (
        [("size", 1.0), ("radius", 0.1)],
        lambda a, p: (lambda h, r: sd_box(p, sub(h, (r, r, r))) - r)(
            mul(vec_of(a["size"]), 0.5), min(a["radius"], min(mul(vec_of(a["size"]), 0.5)))
        ),
        lambda a: 1.0,
    ),
    "plane": ([("normal", (0.0, 1.0, 0.0)), ("offset", 0.0)], lambda a, p: dot(p, a["normal"]) - a["offset"], lambda a: 1.0),
    "torus": (
        [("major", 1.0), ("minor", 0.25)],
        lambda a, p: math.hypot(math.hypot(p[0], p[2]) - a["major"], p[1]) - a["minor"],
        lambda a: 1.0,
    ),
    "capsule": (
        [("height", 1.0), ("radius", 0.25)],
        lambda a, p: norm((p[0], p[1] - min(max(p[1], -a["height"] / 2), a["height"] / 2), p[2])) - a["radius"],
        lambda a: 1.0,
    ),
    "cylinder": (
        [("radius", 0.5), ("height", 1.0)],
        lambda a, p: (lambda dx, dy: min(max(dx, dy), 0.0) + math.hypot(max(dx, 0), max(dy, 0)))(
            math.hypot(p[0], p[2]) - a["radius"], abs(p[1]) - a["height"] / 2
        ),
        lambda a: 1.0,
    ),
    "ellipsoid": (
        [("radii", (1.0, 0.5, 0.5))],
        lambda a, p: (lambda r: (norm((p[0] / r[0], p[1] / r[1], p[2] / r[2])) - 1) * min(r))(
            tuple(max(c, 1e-9) for c in a["radii"])
        ),
        lambda a: 1.0,
    ),
    "octahedron": ([("size", 1.0)], lambda a, p: sd_octahedron(p, a["size"]), lambda a: 1.0),
    "dodecahedron": (
        [("radius", 1.0), ("exponent", 0.0)],
        lambda a, p: gdf_dodecahedron(p, a["radius"], a["exponent"]),
        lambda a: 1.0 if a["exponent"] == 0 else math.sqrt(2) * 6 ** max(0.0, 1 / a["exponent"] - 0.5),
    ),
}


def smin(a, b, k):
    if k <= 0:
        return min(a, b)
    h = max(k - abs(a - b), 0.0) / k
    return min(a, b) - h * h * k * 0.25


def smax(a, b, k):
    return -smin(-a, -b, k)


def falloff(s):
    t = max(1 - s * s, 0.0)
    return t * t * t


FALLOFF_SLOPE = 1.7173003166778396


def round_half_up(x):
    return math.floor(x + 0.5)


def repeat_cell(p, spacing, count):
    q = list(p)
    for i in range(3):
        s = spacing[i]
        if s <= 0:
            continue
        n = count[i]
        if n == 0:
            q[i] = p[i] - s * round_half_up(p[i] / s)
        else:
            half = (n - 1) / 2
            q[i] = p[i] - s * (min(max(round_half_up(p[i] / s + half), 0), n - 1) - half)
    return tuple(q)


def operator(name, a, ch):
    """Builds an operator node over children `ch` (operators.rs, restated)."""
    lams = [c.lam for c in ch]

    def nrm(i, p):
        if lams[i] is None:
            raise ValueError(f"`{name}` needs the lambda of an unannotated implicit child")
        return ch[i].f(p) / lams[i]

    def fold(p, g):
        acc = nrm(0, p)
        for i in range(1, len(ch)):
            acc = g(acc, nrm(i, p))
        return acc

    same = lams[0] if ch else None
    if name == "union":
        return Node(name, lambda p: fold(p, min), 1.0, ch)
    if name == "intersect":
        return Node(name, lambda p: fold(p, max), 1.0, ch)
    if name == "subtract":
        return Node(name, lambda p: fold(p, lambda u, v: max(u, -v)), 1.0, ch)
    if name == "complement":
        return Node(name, lambda p: -ch[0].f(p), same, ch)
    if name == "smooth_union":
        k = a["radius"]
        return Node(name, lambda p: fold(p, lambda u, v: smin(u, v, k)), 1.0, ch)
    if name == "smooth_intersect":
        k = a["radius"]
        return Node(name, lambda p: fold(p, lambda u, v: smax(u, v, k)), 1.0, ch)
    if name == "smooth_subtract":
        k = a["radius"]
        return Node(name, lambda p: fold(p, lambda u, v: smax(u, -v, k)), 1.0, ch)
    if name == "mix":
        w = a["weight"]
        lam = None if None in lams else (1 - w) * lams[0] + w * lams[1]
        return Node(name, lambda p: (1 - w) * ch[0].f(p) + w * ch[1].f(p), lam, ch)
    if name == "blob":
        radius, threshold = a["radius"], a["threshold"]

        def blob(p):
            field, nearest = 0.0, float("inf")
            for i in range(len(ch)):
                d = nrm(i, p)
                field += falloff(max(d, 0.0) / radius)
                nearest = min(nearest, d)
            slope = len(ch) * FALLOFF_SLOPE / radius
            return max((threshold - field) / slope, nearest - radius)

        return Node(name, blob, 1.0, ch)
    if name == "translate":
        off = a["offset"]
        m = lambda p: sub(p, off)
        node = Node(name, lambda p: ch[0].f(m(p)), same, ch, [m])
        node.offset = off
        return node
    if name == "rotate":
        axis, angle = a["axis"], a["angle"]
        m = lambda p: rotate(p, axis, -angle)
        return Node(name, lambda p: ch[0].f(m(p)), same, ch, [m])
    if name == "scale":
        s = vec_of(a["factor"])
        m = lambda p: (p[0] / s[0], p[1] / s[1], p[2] / s[2])
        lam = None if same is None else same * max(s) / min(s)
        return Node(name, lambda p: ch[0].f(m(p)) * min(s), lam, ch, [m])
    if name == "repeat":
        spacing, count = vec_of(a["spacing"]), vec_of(a["count"])
        m = lambda p: repeat_cell(p, spacing, count)
        return Node(name, lambda p: ch[0].f(m(p)), same, ch, [m])
    if name == "mirror":
        n = a["axis"]
        m = lambda p: sub(p, mul(n, 2 * min(dot(p, n), 0.0)))
        return Node(name, lambda p: ch[0].f(m(p)), same, ch, [m])
    if name == "round":
        r = a["radius"]
        return Node(name, lambda p: nrm(0, p) - r, 1.0, ch)
    if name == "onion":
        t = a["thickness"]
        return Node(name, lambda p: abs(nrm(0, p)) - t, 1.0, ch)
    if name == "elongate":
        h = mul(vec_of(a["amount"]), 0.5)
        m = lambda p: tuple(p[i] - min(max(p[i], -h[i]), h[i]) for i in range(3))
        return Node(name, lambda p: ch[0].f(m(p)), same, ch, [m])
    raise ValueError(f"operator `{name}` is not supported by this checker")


OPERATOR_PARAMS = {
    "union": [], "intersect": [], "subtract": [], "complement": [],
    "smooth_union": [("radius", None)], "smooth_intersect": [("radius", None)],
    "smooth_subtract": [("radius", None)], "mix": [("weight", None)],
    "blob": [("radius", 1.0), ("threshold", 0.5)], "translate": [("offset", None)],
    "rotate": [("axis", None), ("angle", None)], "scale": [("factor", None)],
    "repeat": [("spacing", None), ("count", 0.0)], "mirror": [("axis", None)],
    "round": [("radius", None)], "onion": [("thickness", None)], "elongate": [("amount", None)],
}
AXES = {"x": (1.0, 0.0, 0.0), "y": (0.0, 1.0, 0.0), "z": (0.0, 0.0, 1.0)}
UNITS = {None: 1.0, "rad": 1.0, "deg": math.pi / 180}


def bind(name, params, args):
    out, pos = {}, 0
    for key, val in args:
        if key is None:
            key = params[pos][0]
            pos += 1
        out[key] = val
    for key, default in params:
        if key not in out:
            if default is None:
                raise ValueError(f"`{name}` needs `{key}`")
            out[key] = default
    return out


def raw_word(e):
    """A settings value written as a bare word (`shadow hard`), else None."""
    return e[1] if e[0] == "name" else None


class Scene:
    """The scene of a file, evaluated at the parameters' defaults, or at the values in `params`
    (name -> number, angle in radians, or vector) where given."""

    def __init__(self, src, params=None):
        self.lets = {"pi": math.pi, "tau": 2 * math.pi, "time": 0.0}
        self.fns = {}
        self.params = {}  # name -> (default, low, high); low and high None without a range
        self.calls = []  # the fn calls being expanded, outermost first, as written
        self.shapes = []
        self.camera = {"eye": (0.0, 0.0, -5.0), "target": (0.0, 0.0, 0.0), "fov": math.pi / 4, "up": (0.0, 1.0, 0.0)}
        self.max_distance = 100.0
        self.lights = []  # (kind, {key: value or bare word})
        self.materials = {}  # name -> {key: value} (numbers and colours; patterns left out)
        self.annotations = []
        overrides = dict(params or {})
        for st in Parser(src).file():
            if st[0] == "let":
                self.lets[st[1]] = self.value(st[2])
            elif st[0] == "param":
                _, name, default, lo, hi = st
                decl = (self.value(default), None if lo is None else self.value(lo), None if hi is None else self.value(hi))
                self.params[name] = decl
                self.lets[name] = overrides.pop(name, decl[0])
            elif st[0] == "fn":
                self.fns[st[1]] = (st[2], st[3])
            elif st[0] == "block":
                if st[1] == "camera":
                    self.camera.update({k: self.value(e) for k, e in st[3].items()})
                elif st[1] == "trace" and "max_distance" in st[3]:
                    self.max_distance = self.value(st[3]["max_distance"])
                elif st[1] == "light":
                    settings = {}
                    for k, e in st[3].items():
                        settings[k] = raw_word(e) if raw_word(e) is not None else self.value(e)
                    self.lights.append((st[2] or "directional", settings))
                elif st[1] == "material":
                    settings = {}
                    for k, e in st[3].items():
                        if e[0] in ("num", "color", "vec"):
                            settings[k] = self.value(e)
                    self.materials[st[2]] = settings
            elif st[0] == "expr":
                self.shapes.append(self.value(st[1]))
        if "time" in overrides:
            self.lets["time"] = overrides.pop("time")
        if overrides:
            raise ValueError(f"values given for undeclared parameters {sorted(overrides)}")
        shapes = self.shapes
        self.root = shapes[0] if len(shapes) == 1 else Node("scene", lambda p: min(s.f(p) for s in shapes), 1.0, shapes)
        self.find(self.root, lambda p: p)

    def find(self, node, to_local):
        if node.annotation is not None:
            self.annotations.append((node, to_local))
        for child, m in zip(node.children, node.maps):
            self.find(child, lambda p, m=m, t=to_local: m(t(p)))

    def value(self, e, implicit=False):
        k = e[0]
        if k == "num":
            if e[2] not in UNITS:
                raise ValueError(f"unknown unit {e[2]}")
            return e[1] * UNITS[e[2]]
        if k == "color":
            return e[1]
        if k == "vec":
            return tuple(self.value(c, implicit) for c in e[1:])
        if k == "name":
            if e[1] in self.lets:
                return self.lets[e[1]]
            if e[1] in AXES:
                return Field(e[1]) if implicit else AXES[e[1]]
            raise ValueError(f"unknown name {e[1]}")
        if k == "neg":
            v = self.value(e[1], implicit)
            if isinstance(v, Field):
                return Field(f"(-{v.code})")
            return tuple(-c for c in v) if isinstance(v, tuple) else -v
        if k == "bin":
            return self.binary(e[1], self.value(e[2], implicit), self.value(e[3], implicit))
        if k == "call":
            return self.call(e, None, implicit)
        if k == "pipe":
            child = self.value(e[1])
            return self.call(e[2], child, False)
        if k == "tag":
            node = copy.copy(self.value(e[1]))
            node.material = e[2]
            return node
        if k == "comp":
            v = self.value(e[1], implicit)
            return v["xyz".index(e[2])] if isinstance(v, tuple) else v  # colours: not needed here
        if k == "at":
            child = self.value(e[1])
            return operator("translate", {"offset": self.value(e[2])}, [child])
        if k == "annot":
            node = copy.copy(self.value(e[1]))
            (key, arg), = e[3]
            node.lam = float(self.value(arg))
            node.annotation = node.lam
            node.line = e[4]
            node.source = e[5]  # where the `@` is: one annotation in the source, one node per call
            node.calls = tuple(self.calls)
            return node
        raise ValueError(f"cannot evaluate {k}")

    def binary(self, op, a, b):
        if isinstance(a, Field) or isinstance(b, Field):
            if op == "^":
                n = float(b)
                assert n == int(n) and n >= 0, "whole exponents only"
                return Field(f"({code_of(a)}**{int(n)})")
            return Field(f"({code_of(a)} {op} {code_of(b)})")
        if isinstance(a, tuple) or isinstance(b, tuple):
            a3, b3 = vec_of(a), vec_of(b)
            f = {"+": lambda u, v: u + v, "-": lambda u, v: u - v, "*": lambda u, v: u * v, "/": lambda u, v: u / v}[op]
            return tuple(f(u, v) for u, v in zip(a3, b3))
        if op == "+":
            return a + b
        if op == "-":
            return a - b
        if op == "*":
            return a * b
        if op == "/":
            return a / b
        return a**b

    def call(self, e, piped, implicit):
        _, name, args, block, line, text = e
        if name in self.fns:
            return self.expand(name, text, args, piped, implicit)
        if name in MATH:
            vals = [self.value(v, implicit) for _, v in args]
            if any(isinstance(v, Field) for v in vals):
                return Field(f"{name}({', '.join(code_of(v) for v in vals)})")
            return MATH[name](*vals)
        if name == "implicit":
            body = self.value(block[0], implicit=True)
            code = f"lambda p: (lambda x, y, z: {code_of(body)})(p[0], p[1], p[2])"
            return Node("implicit", eval(code, dict(MATH)), None)
        if name in PRIMITIVES:
            params, f, lam = PRIMITIVES[name]
            a = self.args(name, params, args)
            return Node(name, lambda p, a=a: f(a, p), lam(a))
        if name in OPERATOR_PARAMS:
            a = self.args(name, OPERATOR_PARAMS[name], args)
            children = [self.value(b) for b in (block or [])]
            if piped is not None:
                children.insert(0, piped)
            return operator(name, a, children)
        raise ValueError(f"line {line}: unknown call `{name}`")

    def expand(self, name, text, args, piped, implicit):
        """A `fn` call, expanded where it is written: the arguments are computed here, the defaults
        in order with the parameters before them, and the body with them (and what the file
        defines, whose names are all distinct)."""
        params, body = self.fns[name]
        given = [(k, self.value(v, implicit)) for k, v in args]
        if piped is not None:
            given.insert(0, (None, piped))
        bound, pos = {}, 0
        for k, v in given:
            if k is None:
                k = params[pos][0]
                pos += 1
            bound[k] = v
        saved = self.lets
        self.calls.append(" ".join(text.split()))
        try:
            for pname, default in params:
                if pname not in bound:
                    if default is None:
                        raise ValueError(f"`{text}`: `{pname}` is missing")
                    self.lets = {**saved, **bound}
                    bound[pname] = self.value(default, implicit)
            self.lets = {**saved, **bound}
            return self.value(body, implicit)
        finally:
            self.calls.pop()
            self.lets = saved

    def args(self, name, params, args):
        a = bind(name, params, [(k, self.value(v)) for k, v in args])
        for key in ("axis", "normal"):
            if key in a and isinstance(a[key], tuple):
                a[key] = unit(a[key])
        return a


# ---------------------------------------------------------------------------------------------
# Numerics

H = 1e-6


def grad_len(f, p):
    x, y, z = p
    gx = (f((x + H, y, z)) - f((x - H, y, z))) / (2 * H)
    gy = (f((x, y + H, z)) - f((x, y - H, z))) / (2 * H)
    gz = (f((x, y, z + H)) - f((x, y, z - H))) / (2 * H)
    g = math.sqrt(gx * gx + gy * gy + gz * gz)
    return g if math.isfinite(g) else 0.0


def in_ball(rng, c, r):
    while True:
        d = (rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1))
        if dot(d, d) <= 1:
            return add(c, mul(d, r))


def sample_sup(f, hint, rng, extent=12.0, n_global=20000, n_local=3000, climbs=10):
    """The largest |grad f| found: samples in the cube of half size `extent`, in balls around the
    hint (or each of a list of hints), then hill-climbing from the best."""
    hints = hint if isinstance(hint, list) else [hint]
    pts = []
    for _ in range(n_global):
        p = (rng.uniform(-extent, extent), rng.uniform(-extent, extent), rng.uniform(-extent, extent))
        pts.append((grad_len(f, p), p))
    for h in hints:
        for r in (1.0, 0.1, 0.01, 0.001):
            for _ in range(n_local):
                p = in_ball(rng, h, r)
                pts.append((grad_len(f, p), p))
    pts.sort(key=lambda t: -t[0])
    best = pts[0]
    for g, p in pts[:climbs]:
        for step in (1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5):
            for _ in range(40):
                q = add(p, mul((rng.gauss(0, 1), rng.gauss(0, 1), rng.gauss(0, 1)), step))
                gq = grad_len(f, q)
                if gq > g:
                    g, p = gq, q
        if g > best[0]:
            best = (g, p)
    return best


# The frustum sdfc samples is 16:9 (the default image shape): wider than tall. `visible` keeps to
# the square within fov/2 both ways (inside either frustum); `outside the view` uses the wide one.
WIDE = 16 / 9


def in_view(cam, point, aspect=1.0):
    eye, target = cam["eye"], cam["target"]
    fwd = unit(sub(target, eye))
    right = unit(cross(cam["up"], fwd))
    up = cross(fwd, right)
    d = sub(point, eye)
    along = dot(d, fwd)
    lim = math.tan(cam["fov"] / 2)
    return along > 0 and abs(dot(d, right) / along) <= lim * aspect and abs(dot(d, up) / along) <= lim


def blocked(scene, a, b, steps=4000):
    """Where the segment from a to b first enters a solid (a fraction of the way), or None."""
    d = sub(b, a)
    for i in range(1, steps):
        if scene.root.f(add(a, mul(d, i / steps))) <= 0:
            return i / steps
    return None


def visible(scene, point):
    """Problems that keep camera rays from reaching `point`, as a list of strings."""
    eye = scene.camera["eye"]
    problems = []
    if not in_view(scene.camera, point):
        problems.append("outside the view")
    if norm(sub(point, eye)) >= scene.max_distance:
        problems.append("beyond max_distance")
    if scene.root.f(point) < -1e-9:
        problems.append("inside a solid")
    t = blocked(scene, eye, point)
    if t is not None:
        problems.append(f"hidden: the ray enters a solid at t = {t:.3f} of the way")
    return problems


def normal_at(scene, p, h=1e-6):
    f = scene.root.f
    return unit(tuple((f(add(p, mul(e, h))) - f(add(p, mul(e, -h)))) / (2 * h) for e in AXES.values()))


def refract(i, n, eta):
    """GLSL's refract: i the unit direction, n the unit normal against it, eta = n1 / n2."""
    cosi = -dot(n, i)
    k = 1 - eta * eta * (1 - cosi * cosi)
    if k < 0:
        return None
    return unit(add(mul(i, eta), mul(n, eta * cosi - math.sqrt(k))))


def schlick(cosine, ior):
    r0 = ((1 - ior) / (1 + ior)) ** 2
    return r0 + (1 - r0) * (1 - cosine) ** 5


def linear(c):
    """A colour (`#rrggbb`, `#rgb` or a vector in 0..1, sRGB) in linear light."""
    if isinstance(c, str):
        h = c[1:]
        if len(h) == 3:
            h = "".join(ch * 2 for ch in h)
        c = tuple(int(h[i : i + 2], 16) / 255 for i in (0, 2, 4))
    return tuple(v / 12.92 if v <= 0.04045 else ((v + 0.055) / 1.055) ** 2.4 for v in c)


def material_at(scene, p):
    """The settings of the material of the top-level shape whose surface is nearest `p`."""
    shape = min(scene.shapes, key=lambda s: abs(s.f(p)))
    name = getattr(shape, "material", None)
    return scene.materials.get(name, {}) if name else {}


def secondary_ray(scene, how, via, steep):
    """The secondary ray of kind `how` (shadow, reflection, refraction) that leaves the visible
    surface point `via`, as (origin, unit direction, farthest distance), and problems."""
    problems = []
    eye = scene.camera["eye"]
    problems += [f"via {via}: {p}" for p in visible(scene, via) if p != "inside a solid"]
    if abs(scene.root.f(via)) > 1e-6:
        problems.append(f"via {via} is not on a surface: f = {scene.root.f(via):.3g}")
    n = normal_at(scene, via)
    v = unit(sub(via, eye))
    mat = material_at(scene, via)
    R, T, ior = mat.get("reflect", 0.0), mat.get("transparent", 0.0), mat.get("ior", 1.5)
    tint = min(linear(mat.get("color", (0.8, 0.8, 0.8))))
    if how == "shadow":
        # Each light with shadows: the ray from the (lifted) surface towards it.
        best = None
        for kind, s in scene.lights:
            if s.get("shadow", "none") == "none":
                continue
            if kind == "point":
                to = sub(s["position"], via)
                ray = (via, unit(to), norm(to))
            else:
                ray = (via, unit(s.get("direction", (-0.4, 1.0, -0.3))), float("inf"))
            w = sub(steep, via)
            miss = norm(sub(w, mul(ray[1], dot(w, ray[1]))))
            if best is None or miss < best[0]:
                best = (miss, ray)
        if best is None:
            return None, problems + ["no light casts shadows"]
        return best[1], problems
    if how == "reflection":
        cosi = -dot(v, n)
        if R <= 0 or R + T * schlick(cosi, ior) < T * (1 - schlick(cosi, ior)) * tint:
            problems.append(f"the surface at via does not send the ray on as a reflection (reflect {R}, transparent {T})")
        return (via, unit(sub(v, mul(n, 2 * dot(v, n)))), float("inf")), problems
    if how == "refraction":
        cosi = -dot(v, n)
        F = schlick(cosi, ior)
        if T <= 0 or R + T * F >= T * (1 - F) * tint:
            problems.append(f"the refracted lobe is not the heavier at via (reflect {R}, transparent {T}, F {F:.3f})")
        d = refract(v, n, 1 / ior)
        # Through the solid: sphere tracing of -f up to where it is left.
        p = add(via, mul(d, 1e-6))
        for _ in range(100000):
            inside = -scene.root.f(p)
            if inside <= 1e-12:
                break
            p = add(p, mul(d, max(inside, 1e-9)))
        out = normal_at(scene, p)
        cos_out = -dot(d, mul(out, -1))
        e = refract(d, mul(out, -1), ior)
        if e is None:
            return None, problems + ["total internal reflection where the ray leaves the solid"]
        F2 = schlick(dot(e, out), ior)
        if F2 >= 1 - F2:
            problems.append(f"leaving the solid, the reflected lobe is the heavier (F {F2:.3f}, cos {cos_out:.3f})")
        return (p, e, float("inf")), problems
    return None, problems + [f"unknown reached-by: {how}"]


def secondary(scene, how, via, steep):
    """Problems with `steep` being reached only by the secondary ray `how` from `via`."""
    problems = []
    if in_view(scene.camera, steep, WIDE):
        problems.append(f"steep point {steep} is inside the camera's (16:9) frustum")
    if scene.root.f(steep) < -1e-9:
        problems.append(f"steep point {steep} is inside a solid")
    ray, more = secondary_ray(scene, how, via, steep)
    problems += more
    if ray is None:
        return problems
    o, d, far = ray
    w = sub(steep, o)
    s = dot(w, d)
    miss = norm(sub(w, mul(d, s)))
    if s <= 0 or s >= far or miss > 1e-3:
        problems.append(f"the {how} ray from {tuple(round(c, 6) for c in o)} along {tuple(round(c, 6) for c in d)} passes {miss:.3g} from the steep point (at {s:.4g} along)")
    start = add(o, mul(d, 0.01))
    t = blocked(scene, start, steep)
    if t is not None:
        problems.append(f"the {how} ray enters a solid {t:.3f} of the way to the steep point")
    return problems


# ---------------------------------------------------------------------------------------------
# Parameters

# Values a parameter without a range is tried at besides its default: a+1, a-1, 2a+1, -a, a/2,
# 10a+3 (componentwise for a vector). The true constant of such a file is the supremum over these.
PERTURB = [lambda v: v + 1, lambda v: v - 1, lambda v: 2 * v + 1, lambda v: -v, lambda v: v / 2, lambda v: 10 * v + 3]


def vmap(f, v):
    return tuple(f(c) for c in v) if isinstance(v, tuple) else f(v)


def constant(text):
    """A constant written in the language (`2.5`, `60deg`, `(1, 0, 2)`, `pi / 2`)."""
    s = Scene.__new__(Scene)
    s.lets, s.fns, s.calls = {"pi": math.pi, "tau": 2 * math.pi}, {}, []
    return s.value(Parser(text).expr())


def assignments(text):
    """`a = 2.5; t = 60deg` -> {"a": 2.5, "t": 1.047...}."""
    out = {}
    for part in (text or "").split(";"):
        if part.strip():
            name, expr = part.split("=", 1)
            out[name.strip()] = constant(expr)
    return out


def grid_axes(decls):
    """The axes of the parameter grid: (name, component or None, values). A ranged number or
    angle is one axis from low to high, a ranged vector one per component whose range is not a
    point; an unranged parameter one axis of its default and its perturbations."""
    ranged = []
    for name, (default, lo, hi) in decls.items():
        if lo is None:
            continue
        if isinstance(default, tuple):
            ranged += [(name, i, lo[i], hi[i]) for i in range(3) if lo[i] != hi[i]]
        else:
            ranged.append((name, None, lo, hi))
    n = {0: 1, 1: 13, 2: 7, 3: 5}.get(len(ranged), 4)
    axes = [(name, i, [lo + (hi - lo) * k / (n - 1) for k in range(n)]) for name, i, lo, hi in ranged]
    for name, (default, lo, hi) in decls.items():
        if lo is None:
            axes.append((name, None, [default] + [vmap(f, default) for f in PERTURB]))
    return axes


def settings_of(decls, axes, pick):
    """The parameter values with axis k at value pick[k], the rest at their defaults."""
    vals = {name: list(d[0]) if isinstance(d[0], tuple) else d[0] for name, d in decls.items()}
    for (name, i, values), k in zip(axes, pick):
        if i is None:
            vals[name] = list(values[k]) if isinstance(values[k], tuple) else values[k]
        else:
            vals[name][i] = values[k]
    return {name: tuple(v) if isinstance(v, list) else v for name, v in vals.items()}


def old_check_settings(decls):
    """The settings sdfc's check has tried so far: the defaults, every ranged parameter at its
    low end and at its high end together, and each at its ends alone."""
    ranged = {name: d for name, d in decls.items() if d[1] is not None}
    base = {name: d[0] for name, d in decls.items()}
    out = [base]
    if ranged:
        out.append({**base, **{name: d[1] for name, d in ranged.items()}})
        out.append({**base, **{name: d[2] for name, d in ranged.items()}})
        for name, d in ranged.items():
            out += [{**base, name: d[1]}, {**base, name: d[2]}]
    return out


def show(vals):
    def one(v):
        return "(" + ", ".join(f"{c:.4g}" for c in v) + ")" if isinstance(v, tuple) else f"{v:.4g}"

    return "; ".join(f"{k} = {one(v)}" for k, v in vals.items())


def light_sup(node, hint, seed):
    """A cheaper sampling for the many parameter settings of a grid."""
    return sample_sup(node.f, hint, random.Random(seed), n_global=1500, n_local=400, climbs=3)[0]


def the_node(scene, errors):
    """The annotated node (exactly one; for calls, see check_file)."""
    if len(scene.annotations) != 1:
        errors.append(f"{len(scene.annotations)} annotated nodes, expected exactly one")
    return scene.annotations[0]


# ---------------------------------------------------------------------------------------------
# Corpus files

HEADER = ["expect", "true-lipschitz", "annotated", "why"]
MORE = ["class", "exact", "steep-at", "worst-at", "worst-call", "other-steep-at", "reached-by", "via"]


def header(path):
    meta = {}
    with open(path) as fh:
        lines = fh.read().split("\n")
    for i, key in enumerate(HEADER):
        m = re.match(r"// (\S+): (.*)$", lines[i])
        assert m and m.group(1) == key, f"{path}: line {i + 1} must be `// {key}: ...`"
        meta[key] = m.group(2).strip()
    for line in lines[4:]:
        m = re.match(r"// (" + "|".join(MORE) + r"): (.*)$", line)
        if m:
            meta[m.group(1)] = m.group(2).strip()
    return meta


def point_of(text):
    return tuple(float(c) for c in text.strip("()").split(","))


def annotations_in(src):
    """How many `@lipschitz` the source has outside comments."""
    toks = tokenize(src)
    return sum(1 for a, b in zip(toks, toks[1:]) if a[:2] == ("op", "@") and b[1] == "lipschitz")


def sig3(x):
    return float(f"{x:.3g}")


def check_file(path, sdfc=None, seed=1, old=None):
    meta = header(path)
    src = open(path).read()
    cls = meta.get("class", "?")
    errors = []
    notes = []
    exact = eval(meta["exact"], {"sqrt": math.sqrt, "pi": math.pi, "sin": math.sin, "cos": math.cos, "exp": math.exp})
    ann = float(meta["annotated"])
    true3 = float(meta["true-lipschitz"])
    expect = meta["expect"]
    if expect != os.path.basename(os.path.dirname(path)):
        errors.append(f"expect: {expect} in directory {os.path.dirname(path)}")
    if annotations_in(src) != 1:
        errors.append(f"{annotations_in(src)} `@lipschitz` in the source, expected exactly one")
    worst_at = assignments(meta.get("worst-at"))
    base = Scene(src)
    scene = Scene(src, worst_at) if worst_at else base
    steep = point_of(meta["steep-at"])
    rng = random.Random(seed)

    # The annotated node: one, or for an annotation in a `fn` body one per call, the worst call's
    # named by `worst-call` (outermost call first; `a(1) > b(2 * x)` for a call inside a call).
    others = []
    if cls == "call":
        nodes = scene.annotations
        chains = [" > ".join(n.calls) for n, _ in nodes]
        want = " ".join(meta.get("worst-call", "").split())
        match = [i for i, c in enumerate(chains) if c == want or c.startswith(want + " > ")]
        if not all(n.calls for n, _ in nodes):
            errors.append("the annotation is not inside a `fn` body")
        if len(set(chains)) < 2:
            errors.append(f"the annotated fn is expanded by {len(set(chains))} distinct call(s), expected several")
        if not match:
            errors.append(f"worst-call `{want}` is none of the calls {chains}")
            match = [0]
        k = max(match, key=lambda i: grad_len(nodes[i][0].f, nodes[i][1](steep)))
        node, to_local = nodes[k]
        others = [(chains[i], nodes[i][0]) for i in range(len(nodes)) if i != k]
        others_map = {chains[i]: (chains[i], nodes[i][0], nodes[i][1]) for i in range(len(nodes)) if i != k}
        # World points where the other calls are steepest, if the file names them (as hints).
        others_at = [point_of(q) for q in meta.get("other-steep-at", "").split(";") if q.strip()]
        if len({n.source for n, _ in nodes}) != 1:
            errors.append("the call nodes come from several annotations")
    else:
        node, to_local = the_node(scene, errors)
    if node.annotation != ann:
        errors.append(f"header says annotated {ann}, the file says {node.annotation}")
    if abs(true3 - exact) > 0.5 * 10 ** (math.floor(math.log10(exact)) - 2) * 1.0001:
        errors.append(f"true-lipschitz {true3} is not {exact:.6g} to 3 significant digits")
    factor = exact / ann
    tight = abs(ann - exact) <= 1e-9 * exact
    if expect == "wrong" and not 1.05 <= factor <= 10 + 1e-9:
        errors.append(f"factor {factor:.4f} outside [1.05, 10]")
    if expect == "right" and not (tight or 1.01 - 1e-9 <= ann / exact <= 3 + 1e-9):
        errors.append(f"right but annotated/true = {ann / exact:.4f}: neither tight nor x1.01..x3")
    local = to_local(steep)
    g_hint = grad_len(node.f, local)
    if abs(g_hint - exact) > 2e-3 * exact:
        errors.append(f"|grad| at the steep point is {g_hint:.6g}, not {exact:.6g}")
    sup, where = sample_sup(node.f, local, rng)
    if sup > exact * (1 + 1e-6):
        errors.append(f"sampled |grad| {sup:.6g} at {where} exceeds the exact {exact:.6g}")
    if sup < exact * (1 - 2e-3):
        errors.append(f"sampled sup {sup:.6g} stays below the exact {exact:.6g}")

    # Where the steep point is reached from: camera rays, or a secondary ray from `via`.
    how = meta.get("reached-by", "camera")
    if cls == "secondary" and "reached-by" not in meta:
        errors.append("a secondary scene needs `// reached-by:`")
    if how == "camera":
        errors += [f"steep point {steep}: {p}" for p in visible(scene, steep)]
    else:
        if "via" not in meta:
            errors.append(f"reached-by {how} needs `// via:` (the visible point the ray leaves)")
        else:
            errors += secondary(scene, how, point_of(meta["via"]), steep)
        notes.append(f"reached by {how} only")

    # Parameters: right at the defaults; nowhere in the ranges above `exact`; what the ends give.
    ends = None
    if cls == "ranged":
        decls = base.params
        if not decls:
            errors.append("a ranged scene needs a `param`")
        if not worst_at:
            errors.append("a ranged scene needs `// worst-at:`")
        for name in worst_at:
            lo, hi = decls.get(name, (None, None, None))[1:]
            v = worst_at[name]
            if lo is not None and not all(a - 1e-12 <= c <= b + 1e-12 for a, c, b in zip(vec_of(lo), vec_of(v), vec_of(hi))):
                errors.append(f"worst-at {name} = {v} is outside its range {lo}..{hi}")
        d_node, _ = the_node(base, errors)
        d_sup = sample_sup(d_node.f, local, random.Random(seed + 1))[0]
        if d_sup > ann * (1 + 1e-6):
            errors.append(f"at the defaults the slope already reaches {d_sup:.6g} > the annotated {ann}")
        notes.append(f"defaults {d_sup:.4g}")
        axes = grid_axes(decls)
        picks = [()]
        for _, _, values in axes:
            picks = [p + (k,) for p in picks for k in range(len(values))]
        top = (0.0, None)
        for j, pick in enumerate(picks):
            vals = settings_of(decls, axes, pick)
            g = light_sup(the_node(Scene(src, vals), [])[0], local, seed + 2 + j)
            if g > top[0]:
                top = (g, vals)
        if top[0] > exact * (1 + 1e-6):
            errors.append(f"over the ranges the slope reaches {top[0]:.6g} > exact at {show(top[1])}")
        notes.append(f"grid of {len(picks)} settings: max {top[0]:.4g} at {show(top[1])}")
        ends = (0.0, None)
        for j, vals in enumerate(old_check_settings(decls)):
            g = sample_sup(the_node(Scene(src, vals), [])[0].f, local, random.Random(seed + 1000 + j), n_global=5000, n_local=1000, climbs=5)[0]
            if g > ends[0]:
                ends = (g, vals)
        notes.append(f"defaults and range ends (as sdfc samples them): max {ends[0]:.4g} ({'above' if ends[0] > ann * 1.01 else 'within'} the annotation + 1 %)")

    # Calls: every call within `exact`; wrong: the annotation right for some call; right: for all.
    if cls == "call":
        fine = 0
        for j, (chain, other) in enumerate(others):
            # The same place of the body in the other call's frame (an annotated move: moved alike).
            hint = local
            if getattr(node, "offset", None) is not None and getattr(other, "offset", None) is not None:
                hint = add(sub(local, vec_of(node.offset)), vec_of(other.offset))
            hints = [hint] + [to_other(q) for q in others_at for _, _, to_other in [others_map[chain]]]
            g = sample_sup(other.f, hints, random.Random(seed + 3000 + j), n_global=5000, n_local=1000, climbs=5)[0]
            if g > exact * (1 + 1e-6):
                errors.append(f"call {chain}: slope {g:.6g} above the worst call's {exact:.6g}")
            if g <= other.annotation * (1 + 1e-6):
                fine += 1
            elif expect == "right":
                errors.append(f"call {chain}: slope {g:.6g} above its annotation {other.annotation}")
            notes.append(f"{chain}: {g:.4g} (annotated {other.annotation:g})")
        if expect == "wrong" and fine == 0:
            errors.append("the annotation is right for none of the calls")

    result = {
        "file": os.path.relpath(path, HERE),
        "expect": expect,
        "class": cls,
        "exact": exact,
        "true3": meta["true-lipschitz"],
        "annotated": meta["annotated"],
        "factor": factor,
        "tight": tight,
        "sampled": sup,
        "hint": g_hint,
        "errors": errors,
        "notes": notes,
        "where": meta.get("worst-at") or meta.get("worst-call") or (how if cls == "secondary" else ""),
        "ends": ends,
    }
    if old:
        result["old"] = run_sdfc(old, path, [])
    if sdfc:
        runs = run_sdfc(sdfc, path, errors)
        result.update(runs)
        result["flagged"] = runs["quick"]["flagged"]
        result["seen"] = runs["quick"]["seen"]
        result["warnings"] = runs["quick"]["warnings"]
        if expect == "right" and cls in NEW_CLASSES and runs["quick"]["looser"]:
            errors.append("the annotation is above sdfc's inferred bound (for some call or value), so it is not checked")
        # sdfc's own (inferred) bound for the node: annotate it absurdly loose and read the
        # "annotation is looser than the inferred bound" labels (one per call); none means infinite.
        loose = re.sub(r"@lipschitz\([^)]*\)", "@lipschitz(100000)", src)
        run = subprocess.run([sdfc, "check", "-"], input=loose, capture_output=True, text=True)
        found = sorted({float(v) for v in re.findall(r"inferred λ = ([0-9.]+)", run.stdout + run.stderr)})
        result["inferred"] = "/".join(f"{v:g}" for v in found) if found else "∞"
    return result


def run_sdfc(binary, path, errors):
    """`BIN check FILE` (quick) and `BIN check --lipschitz FILE` (thorough): exit code, whether the
    annotation check warned, the slopes it saw, its notes on where (parameter values), and whether
    it said the annotation is above the inferred bound. A non-zero exit is an error."""
    out = {}
    for key, flags in (("quick", []), ("thorough", ["--lipschitz"])):
        run = subprocess.run([binary, "check", *flags, path], capture_output=True, text=True)
        text = run.stdout + run.stderr
        out[key] = {
            "rc": run.returncode,
            "flagged": "the annotated Lipschitz bound is too small" in text,
            "seen": ",".join(re.findall(r"the slope reaches (?:at least )?([0-9.]+)", text)),
            "found": ",".join(re.findall(r"found with ([^\n]*)", text)),
            "looser": "annotation is looser than the inferred bound" in text,
            "warnings": sorted(set(re.findall(r"warning: (.*)", text)) - {"the annotated Lipschitz bound is too small"}),
        }
        if run.returncode != 0:
            errors.append(f"{binary} check {' '.join(flags)} exited {run.returncode}:\n{text}")
    return out


def extra_checks():
    """Two constants that sampling one scene does not settle. Returns a list of problems."""
    problems = []
    # dodecahedron(r, 1): grad = sum sign(p.n_i) n_i; over all 64 sign patterns (a superset of the
    # realisable ones) the longest is 1 + sqrt(5), so that is an upper bound, and prim_dodecahedron's
    # steep point shows it is reached.
    longest = max(
        norm(tuple(sum(s * n[k] for s, n in zip(signs, DODECA)) for k in range(3)))
        for signs in [[(b >> i & 1) * 2 - 1 for i in range(6)] for b in range(64)]
    )
    if abs(longest - (1 + math.sqrt(5))) > 1e-12:
        problems.append(f"dodecahedron: longest sign pattern {longest}, not 1 + sqrt(5)")
    # gyroid: |grad g| on a 64^3 grid over one period, then hill-climbing from the 30 best points,
    # with the analytic gradient of g = sin x cos y + sin y cos z + sin z cos x.
    def g2(p):
        x, y, z = p
        gx = math.cos(x) * math.cos(y) - math.sin(z) * math.sin(x)
        gy = -math.sin(x) * math.sin(y) + math.cos(y) * math.cos(z)
        gz = -math.sin(y) * math.sin(z) + math.cos(z) * math.cos(x)
        return gx * gx + gy * gy + gz * gz

    n = 64
    grid = [(2 * math.pi * i / n, 2 * math.pi * j / n, 2 * math.pi * k / n) for i in range(n) for j in range(n) for k in range(n)]
    best = sorted(((g2(p), p) for p in grid), reverse=True)[:30]
    rng = random.Random(7)
    top = 0.0
    for v, p in best:
        for step in (0.05, 0.01, 0.002, 5e-4, 1e-4):
            for _ in range(150):
                q = add(p, mul((rng.gauss(0, 1), rng.gauss(0, 1), rng.gauss(0, 1)), step))
                w = g2(q)
                if w > v:
                    v, p = w, q
        top = max(top, v)
    if abs(math.sqrt(top) - math.sqrt(3)) > 1e-9:
        problems.append(f"gyroid: max |grad g| found {math.sqrt(top)}, not sqrt(3)")
    return problems


ORDER = {"wrong": 0, "right": 1}
NEW_CLASSES = ("ranged", "secondary", "call")
CLASSES = ["uniform", "far", "thin", "nested", "operator", "primitive", "ranged", "secondary", "call"]


def verdict(r, run):
    """What one sdfc run said about a file: caught / missed (wrong), quiet / false alarm (right)."""
    if r["expect"] == "wrong":
        return f"caught ({run['seen']})" if run["flagged"] else "**missed**"
    return f"**false alarm** ({run['seen']})" if run["flagged"] else "quiet"


def new_table(rows, sdfc, old):
    """The table of the ranged, secondary and call scenes: both checks of the current binary
    (--sdfc) and, with --old, of an older one."""
    print()
    head = "| file | class | true | annotated | factor | worst at / call / reached by | sdfc's inferred λ |"
    if old:
        head += " old quick | old --lipschitz |"
    head += " quick | --lipschitz |"
    print(head)
    print("|" + " --- |" * (head.count("|") - 1))
    for r in rows:
        if r["expect"] == "wrong":
            factor = f"x{r['factor']:.3f}"
        elif r["tight"]:
            factor = "tight"
        else:
            factor = f"loose x{1 / r['factor']:.3f}"
        line = f"| `{r['file']}` | {r['class']} | {r['true3']} | {r['annotated']} | {factor} | {r['where']} | {r.get('inferred', '')} |"
        if old:
            line += f" {verdict(r, r['old']['quick'])} | {verdict(r, r['old']['thorough'])} |"
        if sdfc:
            line += f" {verdict(r, r['quick'])} | {verdict(r, r['thorough'])} |"
        print(line)


def main():
    argv = sys.argv[1:]
    sdfc = None
    table = "--table" in argv
    if "--sdfc" in argv:
        sdfc = argv[argv.index("--sdfc") + 1]
        argv = [a for a in argv if a not in ("--sdfc", sdfc)]
    old = None
    if "--old" in argv:
        old = argv[argv.index("--old") + 1]
        argv = [a for a in argv if a not in ("--old", old)]
    files = [a for a in argv if not a.startswith("--")] or sorted(
        glob.glob(os.path.join(HERE, "wrong", "*.sdf"))
    ) + sorted(glob.glob(os.path.join(HERE, "right", "*.sdf")))
    failed = 0
    rows = []
    for path in files:
        try:
            r = check_file(path, sdfc, old=old)
        except Exception as exc:  # a scene this checker cannot read is a failure too
            print(f"FAIL {path}: {type(exc).__name__}: {exc}")
            failed += 1
            continue
        rows.append(r)
        status = "ok  " if not r["errors"] else "FAIL"
        failed += bool(r["errors"])
        extra = ""
        if sdfc:
            extra = f"  sdfc: {'FLAGGED' if r['flagged'] else 'missed' if r['expect'] == 'wrong' else 'quiet'} {r['seen']}"
        print(f"{status} {r['file']}: exact {r['exact']:.6g}, sampled {r['sampled']:.6g}, at steep point {r['hint']:.6g}, annotated {r['annotated']} (x{r['factor']:.3f}){extra}")
        for n in r["notes"]:
            print(f"       {n}")
        for e in r["errors"]:
            print(f"     {e}")
    for p in extra_checks():
        print(f"FAIL {p}")
        failed += 1
    if table:
        rows.sort(key=lambda r: (ORDER[r["expect"]], not r["tight"], CLASSES.index(r["class"]), r["file"]))
        new_table([r for r in rows if r["class"] in NEW_CLASSES], sdfc, old)
        rows = [r for r in rows if r["class"] not in NEW_CLASSES]
        print()
        print("| file | class | true | annotated | factor | sdfc's inferred λ | current `sdfc check` |")
        print("| --- | --- | --- | --- | --- | --- | --- |")
        for r in rows:
            verdict = ""
            if sdfc:
                if r["expect"] == "wrong":
                    verdict = f"caught (saw {r['seen']})" if r["flagged"] else "**missed**"
                else:
                    verdict = "**false alarm** (saw " + r["seen"] + ")" if r["flagged"] else "quiet"
                if r["warnings"]:
                    verdict += "; also warns: " + "; ".join(r["warnings"])
            if r["expect"] == "wrong":
                factor = f"true = x{r['factor']:.3f} annotated"
            elif r["tight"]:
                factor = "tight (annotated = true)"
            else:
                factor = f"annotated = x{1 / r['factor']:.3f} true"
            print(f"| `{r['file']}` | {r['class']} | {r['true3']} | {r['annotated']} | {factor} | {r.get('inferred', '')} | {verdict} |")
    print(f"\n{len(files) - failed} of {len(files)} scenes pass")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
