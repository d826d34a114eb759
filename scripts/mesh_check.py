#!/usr/bin/env python3
"""Checks mesh files with tools that are not sdfc's: trimesh and manifold3d (PyPI), admesh
(Debian) for STL. Prints one JSON object per file:

  {"file": ..., "trimesh": {"watertight", "winding_consistent", "volume", "euler",
   "faces", "vertices"}, "manifold": {"status", "volume", "genus"}, "admesh": {...} | null}

trimesh merges vertices that share a position (as every tool reading STL must), so a mesh
that is closed only through its own indices, not through its positions, fails here.

Usage: mesh_check.py FILE [FILE ...]
"""
import json
import re
import shutil
import subprocess
import sys

import numpy as np
import trimesh
import manifold3d


def check_trimesh(path):
    mesh = trimesh.load(path, force="mesh", process=True)
    # An OBJ's groups (one per material) load as separate meshes, each with its own copy of
    # the vertices on their borders: join them by position, as a modelling tool does.
    mesh.merge_vertices(merge_tex=True, merge_norm=True)
    return mesh, {
        "watertight": bool(mesh.is_watertight),
        "winding_consistent": bool(mesh.is_winding_consistent),
        "volume": float(mesh.volume),
        "euler": int(mesh.euler_number),
        "faces": int(len(mesh.faces)),
        "vertices": int(len(mesh.vertices)),
    }


def check_manifold(mesh):
    m = manifold3d.Mesh(
        vert_properties=np.asarray(mesh.vertices, dtype=np.float32),
        tri_verts=np.asarray(mesh.faces, dtype=np.uint32),
    )
    solid = manifold3d.Manifold(m)
    return {
        "status": str(solid.status()).split(".")[-1],
        "volume": float(solid.volume()),
        "genus": int(solid.genus()),
    }


def check_admesh(path):
    if not path.lower().endswith(".stl") or shutil.which("admesh") is None:
        return None
    # Without flags admesh only reads, checks and reports (it repairs only what flags ask).
    plain = subprocess.run(["admesh", path], capture_output=True).stdout.decode(
        "utf-8", errors="replace")

    def number(label, text):
        m = re.search(re.escape(label) + r"\s*:\s*(-?[0-9.e+]+)", text)
        return float(m.group(1)) if m else None

    return {
        "parts": number("Number of parts", plain),
        "degenerate_facets": number("Degenerate facets", plain),
        "edges_fixed": number("Edges fixed", plain),
        "facets_removed": number("Facets removed", plain),
        "facets_added": number("Facets added", plain),
        "backwards_edges": number("Backwards edges", plain),
        "normals_fixed": number("Normals fixed", plain),
        "volume": number("Volume", plain),
    }


def main():
    for path in sys.argv[1:]:
        mesh, tm = check_trimesh(path)
        report = {"file": path, "trimesh": tm, "manifold": check_manifold(mesh),
                  "admesh": check_admesh(path)}
        print(json.dumps(report), flush=True)


if __name__ == "__main__":
    main()
