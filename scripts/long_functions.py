#!/usr/bin/env python3
"""Functions longer than a limit, from their `fn` line to their closing brace.

usage: long_functions.py [--max N] DIR [DIR ...]

Prints `file:line name lines` for each function of more than N lines (default 100) in the
`.rs` files under each DIR, test code excluded (`tests.rs`, `tests/` folders and
`#[cfg(test)]` modules), longest first; exits 1 if there is any.
"""

import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from import_graph import strip_comments  # noqa: E402

FN = re.compile(r"\bfn\s+([A-Za-z_][A-Za-z0-9_]*)")


def test_ranges(text):
    """Byte ranges of `#[cfg(test)] mod … { … }` blocks."""
    out = []
    for m in re.finditer(r"#\[cfg\(test\)\]\s*(pub(\([^)]*\))?\s+)?mod\s+\w+\s*\{", text):
        end = match_brace(text, m.end() - 1)
        out.append((m.start(), end))
    return out


def match_brace(text, i):
    depth = 0
    for k in range(i, len(text)):
        if text[k] == "{":
            depth += 1
        elif text[k] == "}":
            depth -= 1
            if depth == 0:
                return k
    return len(text)


def functions(path):
    text = strip_comments(open(path, encoding="utf-8").read())
    skip = test_ranges(text)
    for m in FN.finditer(text):
        if any(a <= m.start() <= b for a, b in skip):
            continue
        # The body's brace: the first `{` after the signature, unless a `;` comes first.
        k = m.end()
        depth = 0
        while k < len(text):
            ch = text[k]
            if ch in "([<":
                depth += 1
            elif ch in ")]>" and depth:
                depth -= 1
            elif ch == ";" and depth == 0:
                k = -1
                break
            elif ch == "{" and depth == 0:
                break
            k += 1
        if k < 0 or k >= len(text):
            continue
        end = match_brace(text, k)
        first = text.count("\n", 0, m.start()) + 1
        last = text.count("\n", 0, end) + 1
        yield first, m.group(1), last - first + 1


def main(argv):
    limit = 100
    if "--max" in argv:
        i = argv.index("--max")
        limit = int(argv[i + 1])
        argv = argv[:i] + argv[i + 2:]
    found = []
    for root in argv:
        for dirpath, dirs, files in os.walk(root):
            dirs[:] = [d for d in dirs if d != "tests"]
            for f in files:
                if f.endswith(".rs") and f != "tests.rs":
                    p = os.path.join(dirpath, f)
                    for line, name, n in functions(p):
                        if n > limit:
                            found.append((n, p, line, name))
    for n, p, line, name in sorted(found, reverse=True):
        print(f"{p}:{line} {name} {n}")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
