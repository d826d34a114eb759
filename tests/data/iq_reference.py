#!/usr/bin/env python3
"""Independent reference values of exact signed distance functions for sdfc.

Run from the repository root:

    python3 tests/data/iq_reference.py > tests/data/iq_reference.csv

Python 3 standard library only, double precision throughout.  The formulas
follow Inigo Quilez's exact distance functions
(https://iquilezles.org/articles/distfunctions/) re-parameterised to the sdfc
conventions below, except where IQ's formula is not exact (spindle torus,
see `sd_torus`), where an own geometric derivation is used.  Every primitive
with a non-trivial formula is cross-checked here against a second, separately
derived closed form (asserts, messages on stderr); the brute-force
surface-sampling check lives in tests/data/verify_reference.py.

sdfc conventions (columns a, b, c of the CSV; unused columns are empty):
  sphere       a = radius                      centred at the origin
  box          a, b, c = full sizes sx, sy, sz  half extents = size / 2
  rounded_box  a = full size s of a cube, b = rounding radius r (inside s):
               IQ round box with half extent s/2 - r, minus r
  plane        a = offset                      normal (0,1,0): d = p.y - offset
  torus        a = major R, b = minor r        ring in the xz plane, axis y
  capsule      a = height h, b = radius r      segment (0,-h/2,0)-(0,h/2,0)
  cylinder     a = radius r, b = height h      axis y, y in [-h/2, h/2]
  cone         a = r1, b = height h, c = r2    axis y, radius r1 at y=-h/2,
                                               r2 at y=+h/2 (r2 = 0: pointed)
  octahedron   a = s                           |x|+|y|+|z| = s, exact distance

The note column is "<where the point is>; <inside|surface|outside>" where the
class is computed from the sign of the distance (|d| <= 1e-12 -> surface).
"""

import math
import sys

SQRT3 = math.sqrt(3.0)
C45 = math.sqrt(0.5)
FAR = 1.0e6


def clamp(x, lo, hi):
    return lo if x < lo else hi if x > hi else x


def length(*c):
    return math.hypot(*c)


# ---------------------------------------------------------------------------
# Closed forms (primary values written to the CSV)
# ---------------------------------------------------------------------------

def sd_sphere(p, r):
    return length(*p) - r


def sd_box_half(p, hx, hy, hz):
    """IQ sdBox with half extents (hx, hy, hz)."""
    qx = abs(p[0]) - hx
    qy = abs(p[1]) - hy
    qz = abs(p[2]) - hz
    return (length(max(qx, 0.0), max(qy, 0.0), max(qz, 0.0))
            + min(max(qx, qy, qz), 0.0))


def sd_box(p, sx, sy, sz):
    return sd_box_half(p, sx / 2.0, sy / 2.0, sz / 2.0)


def sd_rounded_box(p, s, r):
    """IQ sdRoundBox(p, b = s/2, r) == sdBox(p, s/2 - r) - r."""
    b = s / 2.0 - r
    return sd_box_half(p, b, b, b) - r


def sd_plane(p, offset):
    return p[1] - offset


def sd_torus_iq(p, R, r):
    """IQ sdTorus: exact for r <= R (ring / horn torus), and outside always."""
    return length(length(p[0], p[2]) - R, p[1]) - r


def sd_torus(p, R, r):
    """Exact torus distance, also for a spindle torus (r > R).

    In the meridian half-plane (rho >= 0, y) the solid is the disc D of radius
    r centred at (R, 0), cut by rho >= 0.  Outside, the distance is the distance
    to the circle minus r (IQ).  Inside, it is minus the distance to the part of
    the circle boundary with rho >= 0 (the axis segment inside D is interior in
    3D).  If the radial projection of the point from the disc centre falls at
    rho < 0, the nearest boundary point is one of the two poles
    (0, +-sqrt(r^2 - R^2)).
    """
    rho = length(p[0], p[2])
    y = p[1]
    dc = length(rho - R, y)
    f = dc - r
    if f >= 0.0 or r <= R:
        return f
    if dc == 0.0:
        return -r
    proj_rho = R + r * (rho - R) / dc
    if proj_rho >= 0.0:
        return f
    yp = math.sqrt(r * r - R * R)
    return -min(length(rho, y - yp), length(rho, y + yp))


def sd_capsule(p, h, r):
    """IQ sdVerticalCapsule shifted to the segment (0,-h/2,0)-(0,h/2,0)."""
    dy = p[1] - clamp(p[1], -h / 2.0, h / 2.0)
    return length(p[0], dy, p[2]) - r


def sd_cylinder(p, r, h):
    """IQ sdCappedCylinder(p, h/2, r)."""
    dx = length(p[0], p[2]) - r
    dy = abs(p[1]) - h / 2.0
    return min(max(dx, dy), 0.0) + length(max(dx, 0.0), max(dy, 0.0))


def dot2(a, b):
    return a[0] * b[0] + a[1] * b[1]


def sd_cone(p, r1, h, r2):
    """IQ sdCappedCone(p, h/2, r1, r2) (r1 at y=-h/2, r2 at y=+h/2); needs h>0
    or r1 != r2."""
    hh = h / 2.0
    qx = length(p[0], p[2])
    qy = p[1]
    k1 = (r2, hh)
    k2 = (r2 - r1, 2.0 * hh)
    ca = (qx - min(qx, r1 if qy < 0.0 else r2), abs(qy) - hh)
    t = clamp(dot2((k1[0] - qx, k1[1] - qy), k2) / dot2(k2, k2), 0.0, 1.0)
    cb = (qx - k1[0] + k2[0] * t, qy - k1[1] + k2[1] * t)
    s = -1.0 if (cb[0] < 0.0 and ca[1] < 0.0) else 1.0
    return s * math.sqrt(min(dot2(ca, ca), dot2(cb, cb)))


def sd_octahedron(p, s):
    """IQ exact sdOctahedron (with 1/sqrt(3) in full precision)."""
    px, py, pz = abs(p[0]), abs(p[1]), abs(p[2])
    m = px + py + pz - s
    if 3.0 * px < m:
        q = (px, py, pz)
    elif 3.0 * py < m:
        q = (py, pz, px)
    elif 3.0 * pz < m:
        q = (pz, px, py)
    else:
        return m / SQRT3
    k = clamp(0.5 * (q[2] - q[1] + s), 0.0, s)
    return length(q[0], q[1] - s + k, q[2] - k)


# ---------------------------------------------------------------------------
# Second, separately derived closed forms (cross-checks only)
# ---------------------------------------------------------------------------

def seg_dist2d(p, a, b):
    abx, aby = b[0] - a[0], b[1] - a[1]
    apx, apy = p[0] - a[0], p[1] - a[1]
    l2 = abx * abx + aby * aby
    t = 0.0 if l2 == 0.0 else clamp((apx * abx + apy * aby) / l2, 0.0, 1.0)
    return length(apx - t * abx, apy - t * aby)


def sd_revolved_trapezoid(p, r1, h, r2):
    """Cone/cylinder via the meridian profile: distance to the boundary edges
    bottom, slanted side and top (the axis edge is not boundary in 3D)."""
    hh = h / 2.0
    q = (length(p[0], p[2]), p[1])
    d = min(seg_dist2d(q, (0.0, -hh), (r1, -hh)),
            seg_dist2d(q, (r1, -hh), (r2, hh)),
            seg_dist2d(q, (r2, hh), (0.0, hh)))
    inside = (h > 0.0 and -hh <= q[1] <= hh
              and q[0] <= r1 + (r2 - r1) * (q[1] + hh) / h)
    return -d if inside else d


def seg_dist3d(p, a, b):
    ab = [b[i] - a[i] for i in range(3)]
    ap = [p[i] - a[i] for i in range(3)]
    l2 = sum(x * x for x in ab)
    t = 0.0 if l2 == 0.0 else clamp(sum(ap[i] * ab[i] for i in range(3)) / l2,
                                     0.0, 1.0)
    return length(*[ap[i] - t * ab[i] for i in range(3)])


def sd_octahedron_triangle(p, s):
    """Octahedron via the first-octant face triangle: by symmetry the nearest
    boundary point of |p| is on the face (s,0,0),(0,s,0),(0,0,s); inside, the
    nearest facet plane is x+y+z=s."""
    a = [abs(c) for c in p]
    m = (a[0] + a[1] + a[2] - s) / SQRT3
    if m <= 0.0:
        return m
    # projection onto the plane x+y+z=s lies in the triangle iff all its
    # coordinates are >= 0 (they are the barycentric coordinates times s)
    proj = [c - m / SQRT3 for c in a]
    if min(proj) >= 0.0:
        return m
    A, B, C = (s, 0.0, 0.0), (0.0, s, 0.0), (0.0, 0.0, s)
    return min(seg_dist3d(a, A, B), seg_dist3d(a, B, C), seg_dist3d(a, C, A))


def sd_capsule_seg(p, h, r):
    return seg_dist3d(p, (0.0, -h / 2.0, 0.0), (0.0, h / 2.0, 0.0)) - r


def sd_box_cases(p, sx, sy, sz):
    """Box distance by explicit case analysis on the clamped point."""
    h = (sx / 2.0, sy / 2.0, sz / 2.0)
    c = [clamp(p[i], -h[i], h[i]) for i in range(3)]
    out = length(*[p[i] - c[i] for i in range(3)])
    if out > 0.0:
        return out
    return -min(h[i] - abs(p[i]) for i in range(3))


# ---------------------------------------------------------------------------
# Points
# ---------------------------------------------------------------------------

def far_points():
    return [
        (FAR, 0.0, 0.0, "far-axis +x"),
        (0.0, -FAR, 0.0, "far-axis -y"),
        (0.0, 0.0, FAR, "far-axis +z"),
        (FAR, FAR, FAR, "far-diagonal +++"),
        (-FAR, FAR, -FAR, "far-diagonal -+-"),
    ]


def pts_sphere(r):
    return [
        (0.0, 0.0, 0.0, "origin"),
        (0.1, -0.2, 0.15, "near-centre"),
        (0.0, 0.0, -(r - 1e-3), "just under surface -z"),
        (r, 0.0, 0.0, "on surface +x"),
        (0.0, -r, 0.0, "on surface -y"),
        (-r / 3.0, 2.0 * r / 3.0, -2.0 * r / 3.0, "on surface oblique"),
        (r + 0.5, 0.0, 0.0, "outside +x"),
        (r, r, r, "outside diagonal"),
        (-3.0, 4.0, 0.0, "outside (-3 4 0)"),
        (-1.0, -2.0, -2.0, "point (-1 -2 -2)"),
    ] + far_points()


def pts_box(sx, sy, sz):
    hx, hy, hz = sx / 2.0, sy / 2.0, sz / 2.0
    return [
        (0.0, 0.0, 0.0, "origin"),
        (0.1 * hx, -0.1 * hy, 0.05 * hz, "near-centre"),
        (hx - 0.01, 0.2 * hy, -0.1 * hz, "just inside +x face"),
        (0.0, -hy + 0.02, 0.0, "just inside -y face"),
        (hx, 0.5 * hy, -0.25 * hz, "on +x face"),
        (0.25 * hx, -hy, 0.5 * hz, "on -y face"),
        (0.0, 0.0, hz, "on +z face centre"),
        (hx, hy, 0.0, "on edge (z-parallel)"),
        (-hx, 0.5 * hy, -hz, "on edge (y-parallel)"),
        (0.3 * hx, -hy, hz, "on edge (x-parallel)"),
        (hx, hy, hz, "on corner +++"),
        (-hx, -hy, -hz, "on corner ---"),
        (hx, -hy, hz, "on corner +-+"),
        (hx + 0.3, hy + 0.4, 0.0, "beyond edge (nearest: edge) expect 0.5"),
        (-hx - 0.6, 0.0, -hz - 0.8, "beyond edge (nearest: edge) expect 1"),
        (hx + 0.1, -hy - 0.2, hz + 0.2,
         "beyond corner (nearest: corner) expect 0.3"),
        (-hx - 1.0, -hy - 2.0, -hz - 2.0,
         "beyond corner (nearest: corner) expect 3"),
        (0.0, 0.0, -(hz + 0.7), "outside -z face expect 0.7"),
        (0.5 * hx, hy + 1.25, -0.5 * hz, "outside +y face expect 1.25"),
    ] + far_points()


def pts_rounded_box(s, r):
    H = s / 2.0
    b = H - r
    return [
        (0.0, 0.0, 0.0, "origin"),
        (0.1, -0.05, 0.08, "near-centre"),
        (H - 0.01, 0.3 * b, -0.2 * b, "just inside +x face"),
        (b + 0.5 * r * C45, b + 0.5 * r * C45, 0.0,
         "inside near rounded edge (half radius in)"),
        (H, 0.5 * b, -0.5 * b, "on +x face (flat part)"),
        (0.2 * b, -H, 0.0, "on -y face (flat part)"),
        (b + r * C45, b + r * C45, 0.5 * b, "on rounded edge (45 deg)"),
        (-(b + 0.6 * r), 0.3 * b, -(b + 0.8 * r), "on rounded edge (3-4-5)"),
        (b + r / 3.0, -(b + 2.0 * r / 3.0), b + 2.0 * r / 3.0,
         "on rounded corner"),
        (H, H, H, "nominal sharp corner (outside unless r=0)"),
        (H, -H, 0.0, "nominal sharp edge (outside unless r=0)"),
        (H + 0.3, H + 0.3, 0.0, "beyond edge (nearest: edge)"),
        (-(H + 0.2), -(H + 0.2), H + 0.2, "beyond corner (nearest: corner)"),
        (0.0, 0.0, -(H + 0.6), "outside -z face expect 0.6"),
        (H + 1.0, 0.5 * b, 0.0, "outside +x face expect 1"),
    ] + far_points()


def pts_plane(o):
    return [
        (0.0, 0.0, 0.0, "origin"),
        (3.0, o, -7.0, "on plane"),
        (100.0, o, -100.0, "on plane far in-plane"),
        (0.0, o + 2.0, 0.0, "above expect 2"),
        (1.0, o - 0.5, -1.0, "below expect -0.5"),
        (-5.0, o + 0.25, 5.0, "above expect 0.25"),
        (0.5, o + 1e-3, 0.0, "just above"),
        (0.0, o - 10.0, 3.0, "below expect -10"),
        (-2.0, -3.0, 4.0, "point (-2 -3 4)"),
        (FAR, 0.0, 0.0, "far-axis +x (in-plane direction)"),
        (0.0, FAR, 0.0, "far-axis +y"),
        (0.0, -FAR, 0.0, "far-axis -y"),
        (FAR, FAR, FAR, "far-diagonal +++"),
        (-FAR, -FAR, FAR, "far-diagonal --+"),
    ]


def pts_torus(R, r):
    if r > R:  # spindle torus
        yp = math.sqrt(r * r - R * R)
        return [
            (0.0, 0.0, 0.0, "origin (centre; nearest: pole dimple)"),
            (0.0, 0.5 * yp, 0.0, "on axis inside (nearest: pole dimple)"),
            (0.5 * R, 0.0, 0.0, "inside near axis (nearest: pole dimple)"),
            (-0.3 * R, -0.2, 0.4 * R, "inside near axis (nearest: pole dimple)"),
            (0.0, yp, 0.0, "pole dimple on axis"),
            (0.0, -yp, 0.0, "pole dimple on axis -y"),
            (0.0, yp + 0.3, 0.0, "on axis outside above dimple"),
            (R, 0.0, 0.0, "tube centre"),
            (0.6 * R, 0.0, -0.8 * R, "tube centre (3-4-5 angle)"),
            (R + 0.3, 0.3, 0.0, "inside (nearest: outer surface)"),
            (0.1, 0.8, 0.0, "inside near dimple (nearest: outer surface)"),
            (R + r, 0.0, 0.0, "on outer equator"),
            (0.0, r, -R, "on top of tube"),
            (-(R + r * C45), -r * C45, 0.0, "on surface oblique"),
            (R + r - 0.01, 0.0, 0.0, "just inside outer equator"),
            (R + r + 1.0, 0.0, 0.0, "outside equator expect 1"),
            (0.0, -2.0, 0.0, "on axis below"),
            (1.0, 1.0, 1.0, "point (1 1 1)"),
        ] + far_points()
    return [
        (0.0, 0.0, 0.0, "origin (centre of hole)"),
        (R, 0.0, 0.0, "tube centre"),
        (0.6 * R, 0.0, -0.8 * R, "tube centre (3-4-5 angle)"),
        (R, 0.5 * r, 0.0, "inside tube half radius up"),
        (R + r - 0.01, 0.0, 0.0, "just inside outer equator"),
        (R + r, 0.0, 0.0, "on outer equator"),
        (0.0, 0.0, -(R - r), "on inner equator"),
        (0.0, r, -R, "on top of tube"),
        (-0.6 * R, -r, 0.8 * R, "on bottom of tube"),
        (R + r * C45, r * C45, 0.0, "on surface oblique 45 deg"),
        (R + r + 1.0, 0.0, 0.0, "outside equator expect 1"),
        (0.0, r + 0.5, R, "above tube expect 0.5"),
        (0.0, 1.5, 0.0, "on axis above"),
        (0.0, -3.0, 0.0, "on axis below"),
        (1.0, 1.0, 1.0, "point (1 1 1)"),
        (-2.0, 0.5, -1.0, "point (-2 0.5 -1)"),
    ] + far_points()


def pts_capsule(h, r):
    hh = h / 2.0
    return [
        (0.0, 0.0, 0.0, "origin"),
        (0.1, 0.2, -0.1, "near-centre"),
        (r - 0.01, 0.25 * hh, 0.0, "just inside side"),
        (0.0, hh + r - 0.01, 0.0, "just inside top pole"),
        (r, 0.0, 0.0, "on side"),
        (0.0, 0.5 * hh, -r, "on side"),
        (-0.6 * r, -hh, 0.8 * r, "on seam side/bottom cap"),
        (0.0, hh + r, 0.0, "on top pole"),
        (0.0, -hh - r, 0.0, "on bottom pole"),
        (r / 3.0, hh + 2.0 * r / 3.0, -2.0 * r / 3.0, "on top hemisphere"),
        (r + 1.0, 0.25 * hh, 0.0, "outside side expect 1"),
        (0.6, hh + 0.8, 0.0, "beyond top (nearest: top cap)"),
        (-1.0, -(hh + 1.0), 1.0, "beyond bottom diagonal"),
        (2.0, 0.0, -2.0, "outside side diagonal"),
    ] + far_points()


def pts_cylinder(r, h):
    hh = h / 2.0
    return [
        (0.0, 0.0, 0.0, "origin"),
        (0.2 * r, -0.3 * hh, 0.1 * r, "near-centre"),
        (0.0, hh - 0.01, 0.0, "just below top cap"),
        (r - 0.01, 0.0, 0.0, "just inside side"),
        (0.0, hh, 0.0, "on top cap centre"),
        (0.3 * r, -hh, -0.4 * r, "on bottom cap"),
        (r, 0.0, 0.0, "on side"),
        (0.0, 0.5 * hh, -r, "on side"),
        (-0.6 * r, -0.25 * hh, 0.8 * r, "on side"),
        (r, hh, 0.0, "on top rim"),
        (-0.6 * r, -hh, -0.8 * r, "on bottom rim"),
        (r + 0.3, hh + 0.4, 0.0, "beyond top rim (nearest: rim) expect 0.5"),
        (0.6 * (r + 0.6), -(hh + 0.8), 0.8 * (r + 0.6),
         "beyond bottom rim (nearest: rim) expect 1"),
        (0.0, 0.5 * hh, r + 1.0, "outside side expect 1"),
        (0.2 * r, hh + 0.7, -0.3 * r, "above top cap expect 0.7"),
        (-2.0, -3.0, 1.0, "point (-2 -3 1)"),
    ] + far_points()


def pts_cone(r1, h, r2):
    hh = h / 2.0
    rmid = 0.5 * (r1 + r2)
    L = length(r2 - r1, h)
    n = (h / L, (r1 - r2) / L)  # outward normal of the slanted side (rho, y)

    def bis(a, b, k):
        m = (a[0] + b[0], a[1] + b[1])
        lm = length(*m)
        return (k * m[0] / lm, k * m[1] / lm)

    bb = bis((0.0, -1.0), n, 0.5)  # between bottom-cap normal and side normal
    bt = bis((0.0, 1.0), n, 0.5)   # between top-cap normal and side normal
    rq = r1 + 0.25 * (r2 - r1)
    return [
        (0.0, 0.0, 0.0, "origin"),
        (0.1 * rmid, -0.1 * hh, 0.0, "near-centre"),
        (rmid - 0.01 * n[0], -0.01 * n[1], 0.0,
         "just inside side at mid-height"),
        (0.0, -hh, 0.0, "bottom cap centre (apex if r1=0)"),
        (0.0, hh, 0.0, "top cap centre (apex if r2=0)"),
        (0.3 * r1, -hh, 0.4 * r1, "on bottom cap"),
        (r1, -hh, 0.0, "on bottom rim"),
        (0.0, hh, -r2, "on top rim"),
        (rmid, 0.0, 0.0, "on side mid-height"),
        (-rq, -0.5 * hh, 0.0, "on side quarter height"),
        (0.0, 0.0, -(rmid + 0.5 * n[0]), "outside side horizontally"),
        (0.0, 0.5 * n[1], -(rmid + 0.5 * n[0]),
         "outside side along normal expect 0.5"),
        (r1 + bb[0], -hh + bb[1], 0.0,
         "beyond bottom rim (nearest: rim) expect 0.5"),
        (0.0, hh + bt[1], r2 + bt[0],
         "beyond top rim (nearest: rim) expect 0.5"),
        (0.0, hh + 0.7, 0.0, "above top centre expect 0.7"),
        (0.2 * r1, -hh - 0.4, 0.0, "below bottom cap expect 0.4"),
        (1.0, 1.0, 1.0, "point (1 1 1)"),
        (-2.0, -1.0, 0.5, "point (-2 -1 0.5)"),
    ] + far_points()


def pts_octahedron(s):
    c = s / 3.0
    e = 0.5 / SQRT3
    return [
        (0.0, 0.0, 0.0, "origin"),
        (0.1 * s, -0.05 * s, 0.02 * s, "near-centre"),
        (0.5 * s - 0.03, -0.25 * s, 0.25 * s, "just inside face"),
        (s, 0.0, 0.0, "on vertex +x"),
        (0.0, -s, 0.0, "on vertex -y"),
        (0.0, 0.0, s, "on vertex +z"),
        (0.5 * s, 0.5 * s, 0.0, "on edge midpoint"),
        (-0.5 * s, 0.0, -0.5 * s, "on edge midpoint"),
        (0.25 * s, -0.75 * s, 0.0, "on edge"),
        (c, c, c, "on face centroid"),
        (0.5 * s, -0.25 * s, 0.25 * s, "on face"),
        (s + 1.0, 0.0, 0.0, "beyond vertex (nearest: vertex) expect 1"),
        (0.0, -(s + 0.5), 0.0, "beyond vertex (nearest: vertex) expect 0.5"),
        (0.5 * s + 0.3, 0.5 * s + 0.3, 0.0,
         "beyond edge (nearest: edge) expect 0.3*sqrt2"),
        (c + e, c + e, c + e, "beyond face centroid expect 0.5"),
        (-(c + e), c + e, -(c + e), "beyond face centroid expect 0.5"),
        (1.0, 2.0, -3.0, "point (1 2 -3)"),
    ] + far_points()


# ---------------------------------------------------------------------------
# Table
# ---------------------------------------------------------------------------

def rel_close(a, b, tol=1e-12):
    return abs(a - b) <= tol * max(1.0, abs(a), abs(b))


ROWS = []
MAX_CROSS = [0.0]


def cross(name, d, d2, p, params):
    err = abs(d - d2)
    MAX_CROSS[0] = max(MAX_CROSS[0], err / max(1.0, abs(d)))
    assert rel_close(d, d2), (name, params, p, d, d2)


def classify(d):
    if abs(d) <= 1e-12:
        return "surface"
    return "inside" if d < 0.0 else "outside"


def add(name, params, points, fn, check=None, extra_note=None, tag=None):
    """Append rows; points repeated within one parameter set (this happens for
    degenerate shapes, where several placements coincide) are kept once.
    `tag` names a degenerate / special shape and is appended to the note."""
    seen = []
    for (x, y, z, desc) in points:
        p = (float(x), float(y), float(z))
        if p in seen:  # == treats -0.0 and 0.0 alike
            continue
        seen.append(p)
        d = fn(p, *params)
        if check is not None:
            cross(name, d, check(p, *params), p, params)
        note = "%s; %s" % (desc, classify(d))
        if tag:
            note += "; " + tag
        if extra_note is not None:
            e = extra_note(p, d, *params)
            if e:
                note += "; " + e
        cols = [repr(float(v)) for v in params] + [""] * (3 - len(params))
        ROWS.append([name] + cols + [repr(p[0]), repr(p[1]), repr(p[2]),
                                     repr(d), note])


def torus_note(p, d, R, r):
    iq = sd_torus_iq(p, R, r)
    if iq != d:
        return ("IQ sdTorus length(q)-r gives %r here (a bound; not the "
                "exact distance)" % iq)
    return ""


def build():
    for r in (1.0, 2.5, 0.0):
        add("sphere", (r,), pts_sphere(r), sd_sphere,
            check=lambda p, r: length(*p) - r,
            tag="degenerate: point" if r == 0.0 else None)

    for size in ((2.0, 2.0, 2.0), (1.0, 2.0, 3.0), (2.0, 3.0, 0.0)):
        add("box", size, pts_box(*size), sd_box, check=sd_box_cases,
            tag="degenerate: flat rectangle (size z = 0)" if size[2] == 0.0
            else None)

    for (s, r) in ((2.0, 0.25), (2.0, 1.0), (1.0, 0.0)):
        add("rounded_box", (s, r), pts_rounded_box(s, r), sd_rounded_box,
            check=lambda p, s, r: (
                length(*[p[i] - clamp(p[i], -(s / 2 - r), s / 2 - r)
                         for i in range(3)]) - r
                if max(abs(c) for c in p) > s / 2 - r
                else -(s / 2 - max(abs(c) for c in p))),
            tag=("degenerate: sphere (r = s/2)" if r == s / 2 else
                 "degenerate: sharp box (r = 0)" if r == 0.0 else None))

    for o in (0.0, 1.5, -2.0):
        add("plane", (o,), pts_plane(o), sd_plane)

    for (R, r) in ((2.0, 0.5), (0.5, 1.0), (1.0, 0.0), (1.0, 1.0)):
        add("torus", (R, r), pts_torus(R, r), sd_torus,
            check=None if r > R else sd_torus_iq, extra_note=torus_note,
            tag=("spindle torus (minor > major)" if r > R else
                 "degenerate: circle (minor = 0)" if r == 0.0 else
                 "horn torus (minor = major)" if r == R else None))

    for (h, r) in ((2.0, 0.5), (0.0, 1.0), (3.0, 0.0)):
        add("capsule", (h, r), pts_capsule(h, r), sd_capsule,
            check=sd_capsule_seg,
            tag=("degenerate: sphere (h = 0)" if h == 0.0 else
                 "degenerate: segment (r = 0)" if r == 0.0 else None))

    for (r, h) in ((1.0, 2.0), (1.5, 0.5), (0.5, 0.0), (0.0, 2.0)):
        add("cylinder", (r, h), pts_cylinder(r, h), sd_cylinder,
            check=lambda p, r, h: sd_revolved_trapezoid(p, r, h, r),
            tag=("degenerate: disc (h = 0)" if h == 0.0 else
                 "degenerate: segment (r = 0)" if r == 0.0 else None))

    for (r1, h, r2) in ((1.0, 2.0, 0.0), (1.0, 2.0, 0.5), (0.0, 1.5, 1.0),
                        (1.0, 2.0, 1.0)):
        add("cone", (r1, h, r2), pts_cone(r1, h, r2), sd_cone,
            check=sd_revolved_trapezoid,
            tag=("pointed cone (apex at top)" if r2 == 0.0 else
                 "inverted cone (apex at bottom)" if r1 == 0.0 else
                 "r1 = r2: same as cylinder" if r1 == r2 else
                 "frustum"))

    for s in (1.0, 2.5, 0.0):
        add("octahedron", (s,), pts_octahedron(s), sd_octahedron,
            check=sd_octahedron_triangle,
            tag="degenerate: point" if s == 0.0 else None)


def main():
    build()
    out = sys.stdout
    out.write("primitive,a,b,c,px,py,pz,distance,note\n")
    for row in ROWS:
        assert all("," not in f for f in row), row
        out.write(",".join(row) + "\n")
    sys.stderr.write("%d rows; largest relative disagreement with the second "
                     "closed form: %.3g\n" % (len(ROWS), MAX_CROSS[0]))


if __name__ == "__main__":
    main()
