"""The grazing-plane table, transcribed independently of the Rust code (see docs/tracers.md).

The plane y = 0, a ray from height 10 going down at angle θ, exact SDF, ε = 1e-3; every
evaluation of the field counts. `reference_*` follow the conventions of Bán & Valasek's public
reference code (relaxed and enhanced re-enable ω after a fallback step; the auto tracer divides
the slope by the difference of positions); `ours_*` follow sdfc's (Keinert's Listing 2 for
relaxed, and a relative margin of 1e-5 in the overlap test). Run: python3 tests/data/grazing.py
"""
import math

EPS = 1e-3
TOUCH = 1e-5


def plane(theta):
    s = math.sin(math.radians(theta))
    return lambda t: 10 - t * s


def basic(f):
    t, i = 0.0, 0
    while True:
        d = f(t)
        i += 1
        if d < EPS:
            return i
        t += d


def reference_relaxed_or_enhanced(f, kind, omega):
    t, i, di, r0, r = 0.0, 0, 0.0, 0.0, 0.0
    while True:
        if kind == "relaxed":
            di = r * (1.0 if di == 0 else omega)
        else:
            di = r + (0 if di == 0 else omega * r * (di - r0 + r) / max(di + r0 - r, 1e-5))
        r1 = f(t + di)
        i += 1
        if di > r + abs(r1):
            di = 0.0
        else:
            r0, r = r, r1
        t += di
        if r <= EPS:
            return i


def ours_relaxed(f, omega=1.2, keep=False):
    # keep: `fallback keep`, Bálint & Valasek's Algorithm 2 — back to the last safe point
    # t₋ + r₋ with ω kept (prev_r is r₋, signed); otherwise Keinert's listing.
    t, step, prev, prev_r, i = 0.0, 0.0, 0.0, 0.0, 0
    while True:
        r = f(t)
        i += 1
        fail = omega > 1 and (abs(r) + prev) * (1 + TOUCH) < step
        if fail and keep:
            step = prev_r - step
        elif fail:
            step -= omega * step
            omega = 1.0
            prev = abs(r)
        else:
            step = r * omega
            prev, prev_r = abs(r), r
        if not fail and r < EPS:
            return i
        t += step


def ours_enhanced(f, omega=0.9):
    t, d, r0, r, i = 0.0, 0.0, 0.0, 0.0, 0
    while True:
        dn = r if d == 0 else r + omega * r * (d - r0 + r) / max(d + r0 - r, 1e-5 * d)
        rn = f(t + dn)
        i += 1
        if dn > (r + abs(rn)) * (1 + TOUCH):
            d = 0.0
            continue
        t, d, r0, r = t + dn, dn, r, rn
        if r < EPS:
            return i


def auto(f, beta=0.3, touch=0.0, by_positions=True):
    t = 0.0
    r = f(t)
    i, z, m = 1, r, -1.0
    while r >= EPS:
        T = t + z
        R = f(T)
        i += 1
        back = z > (abs(R) + r) * (1 + touch)
        slope = (R - r) / (max(T - t, 1e-5) if by_positions else z)
        m = -1.0 if back else m + (slope - m) * beta
        if not back:
            t, r = T, R
        z = max(EPS, r * max(1.0, 2.0 / max(1.0 - m, 2e-3)))
    return i


def hybrid(f, linear=4.0, refine=4):
    t, t_out, f_out, i = 0.0, 0.0, 0.0, 0
    while True:
        d = f(t)
        i += 1
        if d < 0 and i > 1:
            a, fa, b, fb = t_out, f_out, t, d
            for _ in range(refine):
                tm = a + (b - a) * fa / (fa - fb)
                fm = f(tm)
                i += 1
                if fm > 0:
                    a, fa = tm, fm
                else:
                    b, fb = tm, fm
            return i
        if d < EPS:
            return i
        t_out, f_out = t, d
        t += max(d, linear * EPS)


ANGLES = (45, 10, 1, 0.1)
ROWS = [
    ("basic (closed form)", lambda f: basic(f)),
    ("reference relaxed ω=1.2", lambda f: reference_relaxed_or_enhanced(f, "relaxed", 1.2)),
    ("reference enhanced ω=0.9", lambda f: reference_relaxed_or_enhanced(f, "enhanced", 0.9)),
    ("reference auto β=0.3", lambda f: auto(f)),
    ("ours relaxed ω=1.2", ours_relaxed),
    ("ours relaxed ω=1.2 fallback keep", lambda f: ours_relaxed(f, keep=True)),
    ("ours enhanced ω=0.9", ours_enhanced),
    ("ours hybrid", hybrid),
    ("ours auto β=0.3", lambda f: auto(f, touch=TOUCH, by_positions=False)),
    ("ours auto without the margin", lambda f: auto(f, by_positions=False)),
]
if __name__ == "__main__":
    for name, run in ROWS:
        print(f"{name:30}", [run(plane(a)) for a in ANGLES])
