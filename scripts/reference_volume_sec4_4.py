#!/usr/bin/env python3
"""Independent reference volumes for section 4.4 of 000_0a5975c48c1ac19b.txt: a point swept by three
revolute joints (DH: joint 1 about z with alpha 90 deg, links of 10 and 5, joints 2 and 3 over
[-120, 120] deg), for several ranges [0, T] of joint 1.

Joints 2 and 3 sweep the point over a planar region R (a two-link workspace) in a plane through the
axis of joint 1; joint 1 then turns R. In cylindrical coordinates (rho, phi, z) about that axis a point
is swept when (rho, z) is in R with phi in [0, T], or (-rho, z) is in R with phi in [pi, pi + T].
For each z the sets {rho: (+-rho, z) in R} are computed as unions of intervals (grid plus bisection
on the exact membership test of R), integrated exactly in rho and by Simpson's rule in z.
Run with /usr/bin/python3 (numpy from Debian); prints T in degrees, the number of z steps and V.
"""
import numpy as np, math
L1, L2, lim = 10.0, 5.0, math.radians(120)
def inR(u, w):
    r = np.hypot(u, w); ang = np.arctan2(w, u)
    c = (r**2 - L1**2 - L2**2) / (2*L1*L2)
    ok = np.abs(c) <= 1
    t3 = np.arccos(np.clip(c, -1, 1))
    res = np.zeros(np.shape(u), bool)
    for s in (1, -1):
        th3 = s*t3
        th2 = ang - np.arctan2(L2*np.sin(th3), L1 + L2*np.cos(th3))
        th2 = (th2 + np.pi) % (2*np.pi) - np.pi
        res |= ok & (np.abs(th3) <= lim + 1e-15) & (np.abs(th2) <= lim + 1e-15)
    return res
def intervals(z, sign):
    # {rho in (0,15]: (sign*rho, z) in R} as a list of [a,b], transitions refined by bisection
    N = 6000
    rho = np.linspace(0, 15.0, N+1)
    m = inR(sign*rho, np.full(N+1, z))
    idx = np.nonzero(m[1:] != m[:-1])[0]
    lo = rho[idx].copy(); hi = rho[idx+1].copy(); mlo = m[idx]
    for _ in range(50):
        mid = 0.5*(lo+hi)
        mm = inR(sign*mid, np.full(mid.shape, z))
        same = mm == mlo
        lo = np.where(same, mid, lo); hi = np.where(same, hi, mid)
    t = 0.5*(lo+hi)
    pts = []
    state = m[0]; start = 0.0 if state else None
    for k, x in enumerate(t):
        if state: pts.append((start, x)); state = False
        else: start = x; state = True
    if state: pts.append((start, 15.0))
    return pts
def measure(iv):  # integral of rho drho over union
    return sum((b*b - a*a)/2 for a, b in iv)
def inter(a, b):
    out = []
    for (p, q) in a:
        for (r, s) in b:
            lo, hi = max(p, r), min(q, s)
            if hi > lo: out.append((lo, hi))
    return out
def f(z, T):
    A = intervals(z, 1); B = intervals(z, -1)
    AB = inter(A, B)
    mA, mB, mAB = measure(A), measure(B), measure(AB)
    u = 2*T if T <= math.pi else min(2*math.pi, math.pi + T)
    return T*(mA - mAB) + T*(mB - mAB) + u*mAB
for T in (math.pi/2, math.pi, 1.5*math.pi, 2*math.pi):
    for n in (4000, 8000):
        zs = np.linspace(-15, 15, n+1)
        vals = np.array([f(z, T) for z in zs])
        V = (zs[1]-zs[0])/3*(vals[0] + vals[-1] + 4*vals[1:-1:2].sum() + 2*vals[2:-1:2].sum())
        print(round(math.degrees(T)), n, V, flush=True)
