#!/usr/bin/env python3
"""Independent reference volumes for solids under a planar motion, without any B-rep: seed 001's
path, x -> (0, 4t, 0) + R_x(pi t) x for t in [0, 1], which keeps every plane x = const.

The swept set's section by the plane x = c is the region the body's section there sweeps under the
planar motion (y, z) -> (4t, 0) + R(pi t) (y, z). For the bodies here the section is a rectangle
[-w, w] x [z0, z1] (a box: w constant; a cylinder about z of radius r: w = sqrt(r^2 - c^2)). On a
line z = Z of that plane, each copy of the rectangle meets the line in an interval [a(t), b(t)]
(or not at all), and a continuous family of intervals over a connected set of t covers
[min a, max b]; the section's length on the line is the measure of the union of those over the
connected sets of t where the line meets the copy. So

    area(w) = int length(Z) dZ,   volume = int area(w(c)) dc,

with the t-sets found by sampling and bisection, the extremes by bounded minimisation, and both
integrals by adaptive quadrature. Run with /usr/bin/python3 (numpy and scipy from Debian):

    reference_volume_planar.py box W Z0 Z1 DX     (a box [-DX/2, DX/2] x [-W, W] x [Z0, Z1])
    reference_volume_planar.py cylinder R Z0 Z1   (a cylinder about z of radius R, Z0 <= z <= Z1)

prints the volume.
"""
import math
import sys

import numpy as np
from scipy.integrate import quad
from scipy.optimize import minimize_scalar

SAMPLES = 1001


def corners(w, z0, z1, t):
    """World (y, z) of the section's corners at t (arrays over t)."""
    a = math.pi * t
    c, s = np.cos(a), np.sin(a)
    out = []
    for y, z in ((-w, z0), (w, z0), (w, z1), (-w, z1)):
        out.append((4 * t + c * y - s * z, s * y + c * z))
    return out


def intervals(w, z0, z1, t, Z):
    """Where the copies at t (an array) meet the line z = Z: arrays a, b (nan where they do not)."""
    pts = corners(w, z0, z1, t)
    a = np.full(t.shape, np.inf)
    b = np.full(t.shape, -np.inf)
    for k in range(4):
        (ya, za), (yb, zb) = pts[k], pts[(k + 1) % 4]
        straddles = ((za - Z) * (zb - Z) <= 0) & (za != zb)
        with np.errstate(divide="ignore", invalid="ignore"):
            y = np.where(straddles, ya + (Z - za) / (zb - za) * (yb - ya), np.nan)
        a = np.where(straddles, np.minimum(a, y), a)
        b = np.where(straddles, np.maximum(b, y), b)
    return a, b


def meets(w, z0, z1, t, Z):
    pts = corners(w, z0, z1, t)
    zs = np.array([p[1] for p in pts])
    return (zs.min(axis=0) <= Z) & (zs.max(axis=0) >= Z)


def boundary_t(w, z0, z1, ta, tb, Z):
    """Bisection between ta (meets) and tb (does not)."""
    for _ in range(60):
        tm = 0.5 * (ta + tb)
        if meets(w, z0, z1, np.array([tm]), Z)[0]:
            ta = tm
        else:
            tb = tm
    return ta


def extreme(w, z0, z1, lo, hi, Z, sign):
    """min (sign 1) of a(t) or max (sign -1) of b(t) over the component [lo, hi] of t."""
    def f(t):
        a, b = intervals(w, z0, z1, np.array([min(max(t, lo), hi)]), Z)
        v = a[0] if sign > 0 else -b[0]
        return v if math.isfinite(v) else 1e300
    ts = np.linspace(lo, hi, SAMPLES)
    a, b = intervals(w, z0, z1, ts, Z)
    vals = np.where(np.isfinite(a), a if sign > 0 else -b, 1e300)
    k = int(np.argmin(vals))
    best = float(vals[k])
    h = (hi - lo) / (SAMPLES - 1)
    lo_k, hi_k = max(lo, ts[k] - h), min(hi, ts[k] + h)
    if hi_k > lo_k:
        r = minimize_scalar(f, bounds=(lo_k, hi_k), method="bounded", options={"xatol": 1e-14})
        best = min(best, float(r.fun))
    return best if sign > 0 else -best


def length(w, z0, z1, Z):
    ts = np.linspace(0.0, 1.0, SAMPLES)
    m = meets(w, z0, z1, ts, Z)
    pieces = []
    k = 0
    while k < len(ts):
        if not m[k]:
            k += 1
            continue
        j = k
        while j + 1 < len(ts) and m[j + 1]:
            j += 1
        lo = ts[k] if k == 0 else boundary_t(w, z0, z1, ts[k], ts[k - 1], Z)
        hi = ts[j] if j == len(ts) - 1 else boundary_t(w, z0, z1, ts[j], ts[j + 1], Z)
        pieces.append((extreme(w, z0, z1, lo, hi, Z, 1), extreme(w, z0, z1, lo, hi, Z, -1)))
        k = j + 1
    pieces.sort()
    total, cur_a, cur_b = 0.0, None, None
    for a, b in pieces:
        if cur_b is None or a > cur_b:
            if cur_b is not None:
                total += cur_b - cur_a
            cur_a, cur_b = a, b
        else:
            cur_b = max(cur_b, b)
    if cur_b is not None:
        total += cur_b - cur_a
    return total


def area(w, z0, z1):
    ts = np.linspace(0.0, 1.0, SAMPLES)
    zs = np.array([p[1] for p in corners(w, z0, z1, ts)])
    zmin, zmax = zs.min(), zs.max()
    val, err = quad(lambda Z: length(w, z0, z1, Z), zmin, zmax, limit=400, epsabs=1e-11, epsrel=1e-11)
    return val


def main():
    kind = sys.argv[1]
    if kind == "box":
        w, z0, z1, dx = map(float, sys.argv[2:6])
        print("%.12f" % (dx * area(w, z0, z1)))
    elif kind == "cylinder":
        r, z0, z1 = map(float, sys.argv[2:5])
        # x = r sin(phi): the section's half width is r cos(phi), dx = r cos(phi) dphi
        val, err = quad(lambda phi: area(r * math.cos(phi), z0, z1) * r * math.cos(phi), -math.pi / 2, math.pi / 2,
                        limit=100, epsabs=1e-10, epsrel=1e-10)
        print("%.12f" % val)
    else:
        sys.exit("usage: reference_volume_planar.py box W Z0 Z1 DX | cylinder R Z0 Z1")


if __name__ == "__main__":
    main()
