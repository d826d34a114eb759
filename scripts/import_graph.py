#!/usr/bin/env python3
"""The import graph of a crate's modules, computed from its `use` lines and paths; fails on a cycle.

usage: import_graph.py SRC_DIR [SRC_DIR ...] [--dot] [--edges]

Every `.rs` file under SRC_DIR is a module (`mod.rs`, `lib.rs` and `main.rs` are their
folder's). A path in a file that names another module of the same crate -- in a `use`
(braces expanded), or written inline as `crate::a::b`, `super::x` or `self::y` -- is an edge
from the file's module to the deepest module the path reaches.

Edges are compared between siblings: an edge from `a/b/c` to `a/d/e` is an edge from `a/b`
to `a/d` in the folder `a`. An edge between a module and one of its own ancestors or
descendants (a child naming `super::Thing`, a folder's `mod.rs` calling its children) is
how a folder is made of its files and is not counted. So a cycle reported here is one between
sibling modules: `catalog -> lower -> catalog` at the top, or `check/fn_args <-> check/functions`
inside a folder. `lib.rs` and `main.rs` are the root and never siblings.

Exit status 1 when any folder's sibling graph has a cycle (each is printed with the file and
line of one path that makes each edge), 0 otherwise.
"""

import os
import re
import sys
from collections import defaultdict

IDENT = r"[A-Za-z_][A-Za-z0-9_]*"
INLINE = re.compile(r"\b(crate|super|self)((?:::(?:" + IDENT + r"))+)")


def strip_comments(text):
    """Removes comments and string literals (kept as empty strings), keeping line breaks."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif text.startswith("/*", i):
            depth, i = 1, i + 2
            while i < n and depth:
                if text.startswith("/*", i):
                    depth, i = depth + 1, i + 2
                elif text.startswith("*/", i):
                    depth, i = depth - 1, i + 2
                else:
                    if text[i] == "\n":
                        out.append("\n")
                    i += 1
        elif c == "r" and re.match(r'r#*"', text[i:i + 10]) and (i == 0 or not re.match(r"\w", text[i - 1])):
            m = re.match(r'r(#*)"', text[i:])
            end = '"' + m.group(1)
            j = text.find(end, i + len(m.group(0)))
            j = n if j < 0 else j + len(end)
            out.append('""' + "\n" * text.count("\n", i, j))
            i = j
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            out.append('""' + "\n" * text.count("\n", i, j))
            i = j + 1
        elif c == "'" and re.match(r"'(\\.|[^\\'])'", text[i:i + 4]):
            m = re.match(r"'(\\.|[^\\'])'", text[i:])
            out.append("' '")
            i += len(m.group(0))
        else:
            out.append(c)
            i += 1
    return "".join(out)


def expand_use(tree):
    """`a::{b, c::{d, e}}` -> [[a, b], [a, c, d], [a, c, e]] (aliases and globs dropped)."""
    tree = re.sub(r"\s+as\s+" + IDENT, "", tree)
    tree = re.sub(r"\s+", "", tree)
    paths = []

    def walk(prefix, s):
        depth, start, parts = 0, 0, []
        for k, ch in enumerate(s):
            if ch == "{":
                depth += 1
            elif ch == "}":
                depth -= 1
            elif ch == "," and depth == 0:
                parts.append(s[start:k])
                start = k + 1
        parts.append(s[start:])
        for part in parts:
            if not part:
                continue
            brace = part.find("{")
            if brace >= 0:
                head = [x for x in part[:brace].split("::") if x]
                walk(prefix + head, part[brace + 1:part.rfind("}")])
            else:
                paths.append(prefix + [x for x in part.split("::") if x and x != "*"])

    walk([], tree)
    return paths


def module_of(root, path):
    rel = os.path.relpath(path, root)
    parts = rel[:-3].split(os.sep)
    if parts[-1] in ("mod", "lib", "main"):
        parts = parts[:-1]
    return tuple(parts)


def crate_modules(root):
    mods = {}
    for dirpath, _, files in os.walk(root):
        for f in sorted(files):
            if f.endswith(".rs"):
                p = os.path.join(dirpath, f)
                mods[module_of(root, p)] = p
    return mods


def resolve(mods, here, segs):
    """The deepest module a path names, or None when it leaves the crate."""
    if not segs:
        return None
    if segs[0] == "crate":
        base, rest = (), segs[1:]
    elif segs[0] in ("super", "self"):
        base = here
        rest = segs
        while rest and rest[0] in ("super", "self"):
            if rest[0] == "super":
                base = base[:-1]
            rest = rest[1:]
    else:
        return None
    target = base
    for s in rest:
        cand = target + (s,)
        if cand in mods:
            target = cand
        else:
            break
    return target


def edges_of(root):
    mods = crate_modules(root)
    edges = defaultdict(list)  # (from, to) -> [(file, line)]
    for here, path in mods.items():
        text = strip_comments(open(path, encoding="utf-8").read())
        for m in re.finditer(r"\buse\s+([^;]+);", text):
            line = text.count("\n", 0, m.start()) + 1
            for segs in expand_use(m.group(1)):
                t = resolve(mods, here, segs)
                if t is not None and t != here:
                    edges[(here, t)].append((path, line))
        for m in INLINE.finditer(text):
            segs = [m.group(1)] + [s for s in m.group(2).split("::") if s]
            line = text.count("\n", 0, m.start()) + 1
            t = resolve(mods, here, segs)
            if t is not None and t != here:
                edges[(here, t)].append((path, line))
    return mods, edges


def sibling_edges(edges):
    """Each edge lifted to the two siblings under the deepest folder holding both ends."""
    out = defaultdict(list)
    for (a, b), where in edges.items():
        k = 0
        while k < len(a) and k < len(b) and a[k] == b[k]:
            k += 1
        if k == len(a) or k == len(b):
            continue  # ancestor and descendant
        out[(a[:k + 1], b[:k + 1])].extend(where)
    return out


def cycles(sib):
    """Strongly connected components of more than one module (Tarjan)."""
    graph = defaultdict(set)
    for a, b in sib:
        graph[a].add(b)
        graph.setdefault(b, set())
    index, low, stack, on, comps = {}, {}, [], set(), []
    counter = [0]

    def strong(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                strong(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                comps.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in sorted(graph):
        if v not in index:
            strong(v)
    return comps


def name(m):
    return "/".join(m) or "(root)"


def main(argv):
    roots = [a for a in argv if not a.startswith("--")]
    if not roots:
        print(__doc__)
        return 2
    bad = 0
    for root in roots:
        mods, edges = edges_of(root)
        sib = sibling_edges(edges)
        if "--edges" in argv:
            for (a, b) in sorted(sib):
                print(f"{root}: {name(a)} -> {name(b)}")
        if "--dot" in argv:
            print("digraph {")
            for (a, b) in sorted(sib):
                print(f'  "{name(a)}" -> "{name(b)}";')
            print("}")
        comps = cycles(sib)
        for comp in comps:
            bad += 1
            inside = set(comp)
            print(f"{root}: cycle among {', '.join(name(m) for m in comp)}")
            for (a, b), where in sorted(sib.items()):
                if a in inside and b in inside:
                    f, line = where[0]
                    print(f"  {name(a)} -> {name(b)}  ({f}:{line}, {len(where)} paths)")
        if not comps:
            print(f"{root}: {len(mods)} modules, {len(sib)} sibling edges, no cycle")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
