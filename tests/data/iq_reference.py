#!/usr/bin/env python3
"""Independent reference values of exact signed distance functions for sdfc.

Run from the repository root:

    python3 tests/data/iq_reference.py > tests/data/iq_reference.csv

Python 3 standard library only, double precision throughout.  The formulas
follow Inigo Quilez's exact distance functions
(https://iquilezles.org/articles/distfunctions/) re-parameterised to the sdfc
conventions below, except where IQ's formula is not exact: spindle torus
(`sd_torus`, own geometric derivation), triangular prism (IQ's sdTriPrism is
a bound; the exact 2D triangle is extruded instead) and pyramid (IQ's
sdPyramid ignores the base: fixed below and inside near the base, see
`sd_pyramid`).  Every primitive with a non-trivial formula is cross-checked
here against a second, separately derived closed form (asserts, messages on
stderr); the brute-force surface-sampling check lives in
tests/data/verify_reference.py.

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
  hex_prism    a = inradius r, b = height h    regular hexagon in the xz plane,
                                               flat sides z = +-r, vertices
                                               x = +-2r/sqrt3; y in [-h/2, h/2]
  tri_prism    a = side s, b = depth d         equilateral triangle in the xy
                                               plane, apex up: vertices
                                               (+-s/2, -s/(2 sqrt3)) and
                                               (0, s/sqrt3) (centroid at the
                                               origin); z in [-d/2, d/2]
  pyramid      a = base side s (> 0),          square base of side s in the
               b = height h                    plane y = -h/2, apex (0, h/2, 0)
  round_cone   a = r1, b = r2, c = height h    convex hull of the balls of
                                               radius r1 at (0,-h/2,0) and r2
                                               at (0,h/2,0); the larger ball
                                               when h <= |r1 - r2|
  rounded_cylinder
               a = radius R, b = height H,     axis y, y in [-H/2, H/2], rims
               c = rounding r                  rounded: r -> min(r, R, H/2),
                                               then cylinder(R - r, H - 2r)
                                               offset by r
  link         a = length L, b = radius R,     tube of radius t around the
               c = thickness t                 curve in the plane z = 0:
                                               segments x = +-R, |y| <= L/2,
                                               and half circles of radius R
                                               centred at (0, +-L/2) (for
                                               |y| >= L/2); exact for t <= R
                                               (the reach of the curve)

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


def sign(x):
    """GLSL sign: 0 at 0."""
    return 1.0 if x > 0.0 else -1.0 if x < 0.0 else 0.0


def extrude(d2, w, half):
    """Exact extrusion of an exact 2D distance d2 over |w| <= half."""
    dw = abs(w) - half
    return min(max(d2, dw), 0.0) + length(max(d2, 0.0), max(dw, 0.0))


def sd_hex_prism(p, r, h):
    """IQ sdHexPrism with its hexagon plane (x, y) mapped to sdfc's (x, z)
    and its extrusion axis z mapped to y: inradius r (flat sides z = +-r),
    half-height h/2."""
    kx, ky, kz = -SQRT3 / 2.0, 0.5, 1.0 / SQRT3
    x, z = abs(p[0]), abs(p[2])
    f = 2.0 * min(kx * x + ky * z, 0.0)
    x, z = x - f * kx, z - f * ky
    d2 = length(x - clamp(x, -kz * r, kz * r), z - r) * sign(z - r)
    return extrude(d2, p[1], h / 2.0)


def sd_equilateral_triangle(x, y, s):
    """IQ sdEquilateralTriangle(p, r = s/2): side s, apex up, centroid at the
    origin (exact 2D distance)."""
    k = SQRT3
    r = s / 2.0
    x = abs(x) - r
    y = y + r / k
    if x + k * y > 0.0:
        x, y = (x - k * y) / 2.0, (-k * x - y) / 2.0
    x -= clamp(x, -2.0 * r, 0.0)
    return -length(x, y) * sign(y)


def sd_tri_prism(p, s, d):
    """Exact triangular prism: the exact 2D triangle extruded along z (IQ's
    own sdTriPrism is only a bound)."""
    return extrude(sd_equilateral_triangle(p[0], p[1], s), p[2], d / 2.0)


def sd_pyramid_iq_unit(p, h):
    """IQ sdPyramid verbatim: base square of side 1 in the plane y = 0,
    apex (0, h, 0)."""
    m2 = h * h + 0.25
    px, py, pz = abs(p[0]), p[1], abs(p[2])
    if pz > px:
        px, pz = pz, px
    px -= 0.5
    pz -= 0.5
    qx, qy, qz = pz, h * py - 0.5 * px, h * px + 0.5 * py
    s = max(-qx, 0.0)
    t = clamp((qy - 0.5 * pz) / (m2 + 0.25), 0.0, 1.0)
    a = m2 * (qx + s) * (qx + s) + qy * qy
    b = m2 * (qx + 0.5 * t) * (qx + 0.5 * t) + (qy - m2 * t) * (qy - m2 * t)
    d2 = 0.0 if min(qy, -qx * m2 - qy * 0.5) > 0.0 else min(a, b)
    return math.sqrt((d2 + qz * qz) / m2) * sign(max(qz, -py))


def sd_pyramid(p, s, h):
    """IQ sdPyramid scaled to base side s, base plane y = -h/2, with two fixes
    that make it exact (IQ's formula only measures the four side faces):
    below the base plane the nearest point is on the base square (IQ gives the
    distance to a side face there, e.g. 0.566 instead of 0.4 at
    (0.1, -0.9, 0.05) for s = h = 1), and inside the base plane is a
    candidate too (IQ gives -0.443 instead of -0.01 at (0, -0.49, 0)).  The
    first fix also covers the flat pyramid (h = 0), where IQ gives 0 everywhere
    in the base plane, e.g. at (1, 0, 0) for s = 1 (exact: 0.5)."""
    a = s / 2.0
    y = p[1] + h / 2.0           # height above the base plane
    if y <= 0.0:
        return length(max(abs(p[0]) - a, 0.0), y, max(abs(p[2]) - a, 0.0))
    d = s * sd_pyramid_iq_unit((p[0] / s, y / s, p[2] / s), h / s)
    return max(d, -y) if d < 0.0 else d


def sd_round_cone(p, r1, r2, h):
    """IQ sdRoundCone(p, r1, r2, h) shifted so that the balls are centred at
    y = -h/2 (radius r1) and y = +h/2 (radius r2); for h <= |r1 - r2| (IQ's
    formula undefined) the hull is the larger ball."""
    hh = h / 2.0
    if h <= abs(r1 - r2):
        if r1 >= r2:
            return length(p[0], p[1] + hh, p[2]) - r1
        return length(p[0], p[1] - hh, p[2]) - r2
    b = (r1 - r2) / h
    a = math.sqrt(1.0 - b * b)
    qx, qy = length(p[0], p[2]), p[1] + hh
    k = -b * qx + a * qy
    if k < 0.0:
        return length(qx, qy) - r1
    if k > a * h:
        return length(qx, qy - h) - r2
    return a * qx + b * qy - r1


def sd_rounded_cylinder(p, R, H, r):
    """Cylinder (radius R - r, height H - 2r) offset by r, after clamping r to
    min(r, R, H/2); IQ sdRoundedCylinder re-parameterised."""
    r = min(r, R, H / 2.0)
    return sd_cylinder(p, R - r, H - 2.0 * r) - r


def sd_link(p, L, R, t):
    """IQ sdLink(p, le = L/2, r1 = R, r2 = t)."""
    qx, qy, qz = p[0], max(abs(p[1]) - L / 2.0, 0.0), p[2]
    return length(length(qx, qy) - R, qz) - t


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


def sub3(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def dot3(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross3(a, b):
    return (a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0])


def face_dist(p, n, verts):
    """Distance from p to a convex planar polygon (vertices in order, either
    orientation, unit normal n): the plane distance if the foot of the
    perpendicular is in the polygon, else the nearest edge segment.  A
    polygon of zero area (flat shapes) is just its edges."""
    m = len(verts)
    edges = [(verts[i], verts[(i + 1) % m]) for i in range(m)]
    area = [0.0, 0.0, 0.0]
    for (a, b) in edges:
        c = cross3(a, b)
        area = [area[i] + c[i] for i in range(3)]
    if length(*area) > 0.0:
        dp = dot3(n, sub3(p, verts[0]))
        foot = tuple(p[i] - dp * n[i] for i in range(3))
        sides = [dot3(cross3(sub3(b, a), sub3(foot, a)), n)
                 for (a, b) in edges]
        if min(sides) >= 0.0 or max(sides) <= 0.0:
            return abs(dp)
    return min(seg_dist3d(p, a, b) for (a, b) in edges)


def sd_convex_polytope(p, faces):
    """faces: (unit outward normal n, offset o, vertices) with the solid
    n.x <= o for every face.  Strictly inside: minus the distance to the
    nearest face plane; elsewhere: the distance to the nearest face polygon
    (on a face plane that is 0 on the face and positive beyond it, which also
    covers flat polytopes, where all points of the plane satisfy n.x <= o
    without being on the shape)."""
    planes = [dot3(n, p) - o for (n, o, _) in faces]
    if max(planes) < 0.0:
        return max(planes)
    return min(face_dist(p, n, v) for (n, _, v) in faces)


def prism_faces(poly, normals, offsets, axis, half):
    """Faces of the right prism over a convex polygon poly (2D, in order)
    with edge normals / offsets, extruded along axis 1 (y) or 2 (z) over
    [-half, half].  to3(u, v, w) places the polygon coordinates (u, v) and
    the extrusion coordinate w."""
    if axis == 1:
        def to3(u, v, w):
            return (u, w, v)
    else:
        def to3(u, v, w):
            return (u, v, w)
    faces = []
    m = len(poly)
    for i in range(m):
        (u0, v0), (u1, v1) = poly[i], poly[(i + 1) % m]
        nu, nv = normals[i]
        faces.append((to3(nu, nv, 0.0), offsets[i],
                      [to3(u0, v0, -half), to3(u1, v1, -half),
                       to3(u1, v1, half), to3(u0, v0, half)]))
    for sgn in (1.0, -1.0):
        faces.append((to3(0.0, 0.0, sgn), half,
                      [to3(u, v, sgn * half) for (u, v) in poly]))
    return faces


def sd_hex_prism_polytope(p, r, h):
    """Hexagonal prism as a convex polytope: hexagon vertices at angles
    0, 60, ... deg on the circumradius 2r/sqrt3 in the xz plane; the side
    between vertices k and k+1 has its normal at 30 + 60k deg, offset r."""
    rc = 2.0 * r / SQRT3
    poly = [(rc * math.cos(math.radians(60.0 * k)),
             rc * math.sin(math.radians(60.0 * k))) for k in range(6)]
    normals = [(math.cos(math.radians(30.0 + 60.0 * k)),
                math.sin(math.radians(30.0 + 60.0 * k))) for k in range(6)]
    return sd_convex_polytope(p, prism_faces(poly, normals, [r] * 6, 1,
                                             h / 2.0))


def sd_tri_prism_polytope(p, s, d):
    """Triangular prism as a convex polytope: edge normals (0,-1),
    (sqrt3/2, 1/2), (-sqrt3/2, 1/2) in the xy plane, all at the inradius
    s/(2 sqrt3)."""
    ri = s / (2.0 * SQRT3)
    poly = [(-s / 2.0, -ri), (s / 2.0, -ri), (0.0, s / SQRT3)]
    normals = [(0.0, -1.0), (SQRT3 / 2.0, 0.5), (-SQRT3 / 2.0, 0.5)]
    return sd_convex_polytope(p, prism_faces(poly, normals, [ri] * 3, 2,
                                             d / 2.0))


def sd_pyramid_polytope(p, s, h):
    """Pyramid as a convex polyhedron: the base square (normal -y) and four
    triangles; the +x side has outward normal (h, s/2, 0)/|.| through the
    apex (0, h/2, 0)."""
    a, hh = s / 2.0, h / 2.0
    apex = (0.0, hh, 0.0)
    ln = length(h, a)
    corners = [(a, -hh, a), (a, -hh, -a), (-a, -hh, -a), (-a, -hh, a)]
    faces = [((0.0, -1.0, 0.0), hh, corners)]
    for (nx, nz) in ((1.0, 0.0), (0.0, -1.0), (-1.0, 0.0), (0.0, 1.0)):
        n = (nx * h / ln, a / ln, nz * h / ln)
        base = [c for c in corners if c[0] * nx + c[2] * nz == a]
        faces.append((n, dot3(n, apex), base + [apex]))
    return sd_convex_polytope(p, faces)


def sd_round_cone_min(p, r1, r2, h):
    """The hull of the two balls is the union of the balls B(c(t), r(t)),
    c and r linear in t in [0, 1], so its distance is min_t g(t) with
    g(t) = |p - c(t)| - r(t) (convex): golden-section search.  Also exact
    inside: every inscribed ball of this hull lies in one of the B(c(t), r(t))
    (they are its maximal balls), so some t attains the depth."""
    rho, y = length(p[0], p[2]), p[1]

    def g(t):
        return length(rho, y - (-h / 2.0 + h * t)) - (r1 + (r2 - r1) * t)

    inv = (math.sqrt(5.0) - 1.0) / 2.0
    lo, hi = 0.0, 1.0
    x1, x2 = hi - inv * (hi - lo), lo + inv * (hi - lo)
    f1, f2 = g(x1), g(x2)
    for _ in range(200):
        if hi - lo <= 1e-15:
            break
        if f1 <= f2:
            hi, x2, f2 = x2, x1, f1
            x1 = hi - inv * (hi - lo)
            f1 = g(x1)
        else:
            lo, x1, f1 = x1, x2, f2
            x2 = lo + inv * (hi - lo)
            f2 = g(x2)
    return min(g(0.0), g(1.0), f1, f2, g(0.5 * (lo + hi)))


def sd_rounded_cylinder_profile(p, R, H, r):
    """Meridian quarter-plane (u = rho, v = |y|): the boundary is the side
    segment u = R, the top segment v = H/2 and the quarter circle of radius r
    centred at (R - r, H/2 - r) joining them; sign from a region test."""
    r = min(r, R, H / 2.0)
    hh = H / 2.0
    u, v = length(p[0], p[2]), abs(p[1])
    cu, cv = R - r, hh - r
    d_side = seg_dist2d((u, v), (R, 0.0), (R, cv))
    d_top = seg_dist2d((u, v), (0.0, hh), (cu, hh))
    if u >= cu and v >= cv:  # in the angular range of the quarter circle
        d_arc = abs(length(u - cu, v - cv) - r)
    else:
        d_arc = min(length(u - R, v - cv), length(u - cu, v - hh))
    d = min(d_side, d_top, d_arc)
    inside = (u <= R and v <= hh
              and (u <= cu or v <= cv or length(u - cu, v - cv) <= r))
    return -d if inside else d


def arc_dist3d(p, cy, R, upper):
    """Distance from p to the half circle of radius R centred at (0, cy, 0) in
    the plane z = 0, upper (y >= cy) or lower (y <= cy) half."""
    x, y, z = p[0], p[1] - cy, p[2]
    rho = length(x, y)
    if rho == 0.0:
        return length(R, z)
    if (y >= 0.0) if upper else (y <= 0.0):
        return length(rho - R, z)
    return min(length(x - R, y, z), length(x + R, y, z))


def sd_link_curve(p, L, R, t):
    """Distance to the stadium curve (two segments, two half-circle arcs)
    minus t."""
    hl = L / 2.0
    d = min(seg_dist3d(p, (R, -hl, 0.0), (R, hl, 0.0)),
            seg_dist3d(p, (-R, -hl, 0.0), (-R, hl, 0.0)),
            arc_dist3d(p, hl, R, True),
            arc_dist3d(p, -hl, R, False))
    return d - t


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


def pts_hex_prism(r, h):
    hh = h / 2.0
    rc = 2.0 * r / SQRT3         # vertex distance (on the x axis)
    n = (SQRT3 / 2.0, 0.5)       # normal (x, z) of a slanted side
    return [
        (0.0, 0.0, 0.0, "origin"),
        (0.1 * r, -0.2 * hh, 0.05 * r, "near-centre"),
        (0.2 * r, 0.3 * hh, r - 0.01, "just inside +z side"),
        ((r - 0.01) * n[0], -0.1 * hh, (r - 0.01) * n[1],
         "just inside slanted side"),
        (0.1 * r, hh - 0.01, -0.2 * r, "just below top cap"),
        (0.3 * r, 0.5 * hh, r, "on +z side"),
        (r * n[0], -0.25 * hh, -r * n[1], "on slanted side centre line"),
        (0.2 * r, hh, 0.1 * r, "on top cap"),
        (0.0, -hh, 0.0, "on bottom cap centre"),
        (rc, 0.3 * hh, 0.0, "on vertical edge (hexagon vertex +x)"),
        (-0.5 * rc, -0.5 * hh, r, "on vertical edge (hexagon vertex -x +z)"),
        (0.0, hh, r, "on top rim (edge midpoint +z)"),
        (-r * n[0], -hh, r * n[1], "on bottom rim (slanted edge midpoint)"),
        (rc, hh, 0.0, "on corner (top +x vertex)"),
        (0.2 * r, 0.1 * hh, r + 0.5, "outside +z side expect 0.5"),
        ((r + 0.5) * n[0], 0.2 * hh, (r + 0.5) * n[1],
         "outside slanted side along normal expect 0.5"),
        (rc + 0.5, -0.3 * hh, 0.0,
         "beyond vertical edge (nearest: edge) expect 0.5"),
        (0.1 * r, hh + 0.7, 0.0, "above top cap expect 0.7"),
        (0.0, -(hh + 0.3), -(r + 0.4),
         "beyond bottom rim (nearest: rim) expect 0.5"),
        (rc + 0.3, hh + 0.4, 0.0,
         "beyond top corner (nearest: corner) expect 0.5"),
        (1.0, 1.0, 1.0, "point (1 1 1)"),
        (-2.0, 0.5, 1.5, "point (-2 0.5 1.5)"),
    ] + far_points()


def pts_tri_prism(s, d):
    hd = d / 2.0
    ri = s / (2.0 * SQRT3)       # inradius: bottom side at y = -ri
    top = s / SQRT3              # apex y
    n = (SQRT3 / 2.0, 0.5)       # normal (x, y) of the right side
    v = (SQRT3 / 2.0, -0.5)      # bisector at the bottom-right vertex
    return [
        (0.0, 0.0, 0.0, "origin (centroid)"),
        (0.05 * s, -0.05 * s, 0.1 * hd, "near-centre"),
        (0.1 * s, -ri + 0.01, 0.0, "just inside bottom side"),
        ((ri - 0.01) * n[0], (ri - 0.01) * n[1], -0.2 * hd,
         "just inside right side"),
        (0.0, 0.0, hd - 0.01, "just inside front cap"),
        (0.2 * s, -ri, 0.5 * hd, "on bottom side"),
        (ri * n[0], ri * n[1], 0.0, "on right side (foot of inradius)"),
        (-ri * n[0], ri * n[1], -0.3 * hd, "on left side (foot of inradius)"),
        (0.1 * s, 0.0, hd, "on front cap"),
        (0.0, top, 0.25 * hd, "on apex edge"),
        (s / 2.0, -ri, -0.5 * hd, "on bottom-right edge"),
        (0.0, -ri, -hd, "on back rim (bottom side midpoint)"),
        (s / 2.0, -ri, hd, "on corner (bottom-right front)"),
        (0.0, top, -hd, "on corner (apex back)"),
        (0.1 * s, -ri - 0.5, 0.2 * hd, "outside bottom side expect 0.5"),
        ((ri + 0.5) * n[0], (ri + 0.5) * n[1], 0.0,
         "outside right side along normal expect 0.5"),
        (0.0, top + 0.5, -0.2 * hd,
         "beyond apex edge (nearest: edge) expect 0.5"),
        (s / 2.0 + 0.5 * v[0], -ri + 0.5 * v[1], 0.1 * hd,
         "beyond bottom-right edge (nearest: edge) expect 0.5"),
        (0.05 * s, 0.0, hd + 0.7, "outside front cap expect 0.7"),
        (0.0, -ri - 0.3, -(hd + 0.4),
         "beyond back rim (nearest: rim) expect 0.5"),
        (s / 2.0 + 0.3 * v[0], -ri + 0.3 * v[1], hd + 0.4,
         "beyond front corner (nearest: corner) expect 0.5"),
        (1.0, 1.0, 1.0, "point (1 1 1)"),
        (-1.5, -0.5, 0.25, "point (-1.5 -0.5 0.25)"),
    ] + far_points()


def pts_pyramid(s, h):
    a, hh = s / 2.0, h / 2.0
    ln = length(h, a)
    n = (h / ln, a / ln)         # normal (x, y) of the +x side
    cen = (2.0 * a / 3.0, -hh / 3.0)  # centroid (x, y) of the +x side
    return [
        (0.0, 0.0, 0.0, "origin (mid-height on axis)"),
        (0.05 * a, -0.1 * hh, 0.05 * a, "near-centre"),
        (0.0, -hh + 0.01, 0.0, "just above base centre"),
        (0.6 * a, -hh + 0.05, -0.3 * a,
         "just above base near +x side (nearest: base)"),
        (0.5 * a - 0.01 * n[0], -0.01 * n[1], 0.0,
         "just inside +x side at mid-height"),
        (0.0, hh - 0.01, 0.0, "just below apex"),
        (0.0, -hh, 0.0, "on base centre"),
        (0.3 * a, -hh, -0.4 * a, "on base"),
        (0.0, hh, 0.0, "on apex"),
        (0.5 * a, 0.0, 0.0, "on +x side at mid-height"),
        (-0.3 * a, 0.0, -0.5 * a, "on -z side at mid-height"),
        (cen[0], cen[1], 0.0, "on +x side centroid"),
        (0.5 * a, 0.0, 0.5 * a, "on lateral edge midpoint"),
        (a, -hh, 0.3 * a, "on base edge"),
        (a, -hh, a, "on base corner +x+z"),
        (-a, -hh, -a, "on base corner -x-z"),
        (0.5 * a + 0.5 * n[0], 0.5 * n[1], 0.0,
         "outside +x side along normal expect 0.5"),
        (-0.2 * a, cen[1] + 0.5 * n[1], -(cen[0] + 0.5 * n[0]),
         "outside -z side along normal expect 0.5"),
        (0.2 * a, -hh - 0.4, 0.1 * a, "below base expect 0.4"),
        (0.0, hh + 0.5, 0.0, "above apex (nearest: apex) expect 0.5"),
        (a + 0.3, -hh - 0.3, 0.1 * a,
         "beyond base edge (nearest: edge) expect 0.3*sqrt2"),
        (a + 0.3, -hh - 0.3, a + 0.3,
         "beyond base corner (nearest: corner) expect 0.3*sqrt3"),
        (a + 0.5, -hh, 0.0, "in base plane outside +x edge"),
        (-(a + 0.5), -hh - 0.1, 0.2 * a, "below base plane beside -x edge"),
        (a + 0.2, -hh + 0.1, 0.0, "beside +x side just above base"),
        (1.0, 1.0, 1.0, "point (1 1 1)"),
        (-0.5, -2.0, 0.25, "point (-0.5 -2 0.25)"),
    ] + far_points()


def pts_round_cone(r1, r2, h):
    hh = h / 2.0
    c1, c2 = -hh, hh             # ball centres on the y axis
    if h <= abs(r1 - r2):        # nested: the larger ball
        big_c, big_r = (c1, r1) if r1 >= r2 else (c2, r2)
        sm_c, sm_r = (c2, r2) if r1 >= r2 else (c1, r1)
        return [
            (0.0, 0.0, 0.0, "origin"),
            (0.0, big_c, 0.0, "larger ball centre"),
            (0.0, sm_c, 0.0, "smaller ball centre (inside larger)"),
            (0.0, sm_c + sm_r, 0.0, "smaller ball pole (inside larger)"),
            (big_r, big_c, 0.0, "on larger ball equator"),
            (0.0, big_c + big_r, 0.0, "on larger ball top pole"),
            (0.0, big_c - big_r, 0.0, "on larger ball bottom pole"),
            (big_r / 3.0, big_c + 2.0 * big_r / 3.0, -2.0 * big_r / 3.0,
             "on larger ball oblique"),
            (big_r - 0.01, big_c, 0.0, "just inside equator"),
            (0.0, big_c + big_r + 0.5, 0.0, "above top pole expect 0.5"),
            (0.0, big_c - big_r - 0.7, 0.0, "below bottom pole expect 0.7"),
            (0.0, big_c, -(big_r + 1.0), "outside equator expect 1"),
            (1.0, 1.0, 1.0, "point (1 1 1)"),
        ] + far_points()
    b = (r1 - r2) / h
    a = math.sqrt(1.0 - b * b)
    n = (a, b)                   # outward normal (rho, y) of the cone side

    def unit(u, v):
        lu = length(u, v)
        return (u / lu, v / lu)

    nb = unit(a, b - 1.0)        # between the bottom pole and the side
    nt = unit(a, b + 1.0)        # between the top pole and the side
    t1 = (r1 * n[0], c1 + r1 * n[1])  # tangent circles of the side
    t2 = (r2 * n[0], c2 + r2 * n[1])
    mid = (0.5 * (t1[0] + t2[0]), 0.5 * (t1[1] + t2[1]))
    return [
        (0.0, 0.0, 0.0, "origin"),
        (0.05, 0.1, -0.05, "near-centre"),
        (0.0, c1, 0.0, "bottom ball centre expect -r1"),
        (0.0, c2, 0.0, "top ball centre expect -r2"),
        (mid[0] - 0.01 * n[0], mid[1] - 0.01 * n[1], 0.0,
         "just inside side"),
        (0.0, c1 - r1 + 0.01, 0.0, "just inside bottom pole"),
        (0.0, c1 - r1, 0.0, "on bottom pole"),
        (0.0, c2 + r2, 0.0, "on top pole"),
        (mid[0], mid[1], 0.0, "on side mid-way"),
        (0.0, mid[1], -mid[0], "on side mid-way (-z)"),
        (0.6 * t1[0], t1[1], 0.8 * t1[0], "on lower tangent circle"),
        (-t2[0], t2[1], 0.0, "on upper tangent circle"),
        (r1 * nb[0], c1 + r1 * nb[1], 0.0, "on bottom cap oblique"),
        (0.0, c2 + r2 * nt[1], r2 * nt[0], "on top cap oblique"),
        (mid[0] + 0.5 * n[0], mid[1] + 0.5 * n[1], 0.0,
         "outside side along normal expect 0.5"),
        ((r1 + 0.5) * nb[0], c1 + (r1 + 0.5) * nb[1], 0.0,
         "outside bottom cap oblique expect 0.5"),
        (0.0, c2 + (r2 + 0.5) * nt[1], -(r2 + 0.5) * nt[0],
         "outside top cap oblique expect 0.5"),
        (0.0, c1 - r1 - 0.4, 0.0, "below bottom pole expect 0.4"),
        (0.0, c2 + r2 + 0.7, 0.0, "above top pole expect 0.7"),
        (1.0, 1.0, 1.0, "point (1 1 1)"),
        (-2.0, -1.0, 0.5, "point (-2 -1 0.5)"),
    ] + far_points()


def pts_rounded_cylinder(R, H, r):
    r = min(r, R, H / 2.0)
    hh = H / 2.0
    cu, cv = R - r, hh - r       # centre (rho, y) of the upper rim arc
    return [
        (0.0, 0.0, 0.0, "origin"),
        (0.1 * R, -0.1 * hh, 0.05 * R, "near-centre"),
        (R - 0.01, 0.5 * cv, 0.0, "just inside side"),
        (0.5 * cu, hh - 0.01, 0.0, "just below top (flat part)"),
        (cu + 0.5 * r * C45, cv + 0.5 * r * C45, 0.0,
         "inside near rim (half radius in)"),
        (0.0, 0.5 * cv, -R, "on side (flat part)"),
        (-0.6 * R, -0.25 * cv, 0.8 * R, "on side (flat part)"),
        (0.5 * cu, hh, 0.0, "on top (flat part)"),
        (0.0, -hh, 0.0, "on bottom centre"),
        (cu + r * C45, cv + r * C45, 0.0, "on upper rim (45 deg)"),
        (0.0, -(cv + 0.8 * r), -(cu + 0.6 * r), "on lower rim (3-4-5)"),
        (R, hh, 0.0, "nominal sharp rim (outside unless r = 0)"),
        (R + 1.0, 0.5 * cv, 0.0, "outside side expect 1"),
        (0.5 * cu, hh + 0.7, 0.0, "above top expect 0.7"),
        (0.0, -(hh + 0.4), 0.3 * cu, "below bottom expect 0.4"),
        (cu + (r + 0.5) * C45, cv + (r + 0.5) * C45, 0.0,
         "beyond upper rim (45 deg) expect 0.5"),
        (1.0, 1.0, 1.0, "point (1 1 1)"),
        (-2.0, -3.0, 1.0, "point (-2 -3 1)"),
    ] + far_points()


def pts_link(L, R, t):
    hl = L / 2.0
    return [
        (0.0, 0.0, 0.0, "origin (centre of the hole) expect R - t"),
        (0.05, 0.1, 0.0, "near-centre"),
        (R, 0.0, 0.0, "on centre curve (straight part) expect -t"),
        (-R, 0.5 * hl, 0.0, "on centre curve (straight part) expect -t"),
        (0.0, hl + R, 0.0, "on centre curve (top of upper arc) expect -t"),
        (-R * C45, -hl - R * C45, 0.0,
         "on centre curve (lower arc 45 deg) expect -t"),
        (R, hl, 0.0, "on centre curve (seam) expect -t"),
        (R + 0.5 * t, -0.5 * hl, 0.0, "inside tube half thickness out"),
        (R, 0.25 * hl, t - 0.01, "just inside tube (+z)"),
        (R + t, 0.25 * hl, 0.0, "on tube (straight part outer)"),
        (-(R - t), -0.25 * hl, 0.0, "on tube (straight part inner)"),
        (R, 0.0, -t, "on tube (straight part -z)"),
        (0.0, hl + R + t, 0.0, "on tube (upper arc outer)"),
        (0.0, -(hl + R - t), 0.0, "on tube (lower arc inner)"),
        ((R + t) * 0.6, hl + (R + t) * 0.8, 0.0, "on tube (upper arc 3-4-5)"),
        (R + t, hl, 0.0, "on tube (seam outer)"),
        (R + t + 1.0, 0.0, 0.0, "outside straight part expect 1"),
        (0.0, -(hl + R + t + 0.5), 0.0, "outside lower arc expect 0.5"),
        (-R, hl, t + 0.7, "above seam (+z) expect 0.7"),
        (0.0, 0.0, 2.0, "on z axis"),
        (0.0, hl + 0.3 * R, 0.0, "in the hole near upper arc centre"),
        (1.0, 2.0, -0.5, "point (1 2 -0.5)"),
        (-2.0, -1.0, 0.25, "point (-2 -1 0.25)"),
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

    for (r, h) in ((1.0, 2.0), (0.5, 3.0), (1.0, 0.0)):
        add("hex_prism", (r, h), pts_hex_prism(r, h), sd_hex_prism,
            check=sd_hex_prism_polytope,
            tag="degenerate: flat hexagon (h = 0)" if h == 0.0 else None)

    for (s, d) in ((1.0, 2.0), (2.0, 0.5), (1.5, 0.0)):
        add("tri_prism", (s, d), pts_tri_prism(s, d), sd_tri_prism,
            check=sd_tri_prism_polytope,
            tag="degenerate: flat triangle (depth 0)" if d == 0.0 else None)

    for (s, h) in ((1.0, 1.0), (2.0, 0.5), (1.0, 3.0), (1.0, 0.0)):
        add("pyramid", (s, h), pts_pyramid(s, h), sd_pyramid,
            check=sd_pyramid_polytope,
            tag="degenerate: flat square (h = 0)" if h == 0.0 else None)

    for (r1, r2, h) in ((1.0, 0.5, 2.0), (0.25, 0.75, 1.5), (0.5, 0.5, 2.0),
                        (1.0, 0.25, 0.5), (0.5, 1.0, 0.5)):
        add("round_cone", (r1, r2, h), pts_round_cone(r1, r2, h),
            sd_round_cone, check=sd_round_cone_min,
            tag=("nested: bottom ball only (h < r1 - r2)" if h < r1 - r2 else
                 "nested and tangent: top ball only (h = r2 - r1)"
                 if h == r2 - r1 else
                 "r1 = r2: capsule" if r1 == r2 else None))

    for (R, H, r) in ((1.0, 2.0, 0.25), (1.5, 1.0, 0.2), (1.0, 2.0, 0.0),
                      (0.5, 3.0, 1.0), (1.0, 1.0, 0.8)):
        add("rounded_cylinder", (R, H, r), pts_rounded_cylinder(R, H, r),
            sd_rounded_cylinder, check=sd_rounded_cylinder_profile,
            tag=("degenerate: sharp cylinder (r = 0)" if r == 0.0 else
                 "r clamped to R: capsule" if min(r, H / 2.0) >= R else
                 "r clamped to H/2: rounded disc" if r >= H / 2.0 else None))

    for (L, R, t) in ((2.0, 1.0, 0.25), (1.0, 0.5, 0.1), (0.0, 1.0, 0.25)):
        add("link", (L, R, t), pts_link(L, R, t), sd_link,
            check=sd_link_curve,
            tag="degenerate: torus in the xy plane (L = 0)" if L == 0.0
            else None)


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
