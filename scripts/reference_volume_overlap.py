#!/usr/bin/python3
"""Reference volume for examples/sphere_spring_overlap.json (no closed form: the turns overlap).

The entity is the unit ball centred c = (4, 0, 0); the motion is the screw about the z axis through
the origin with pitch 1.5 per turn, angle theta in [0, 5 pi] (2.5 turns):
    M(theta) x = Rz(theta) x + (0, 0, h theta),   h = 1.5 / (2 pi).
A point x is in the swept set iff min over theta of |M(theta)^-1 x - c| <= 1. In cylindrical
coordinates (rho, phi, z) that squared distance is
    g(theta) = rho^2 + 16 - 8 rho cos(phi - theta) + (z - h theta)^2.

Two independent estimates are computed:

1. Slice integration (the reference value). The screw motion keeps rho fixed, so on the cylinder of
   radius rho the swept set is the union over integers k of M_rho + (2 pi k, 0), where M_rho is the
   Minkowski sum, in the unrolled (u, z) plane, of the ball's section
       D_rho = {(psi, zeta): zeta^2 <= 8 rho cos(psi) - rho^2 - 15}
   with the segment {s (1, h): s in [0, 5 pi]}. D_rho is convex (zeta's half width is the square
   root of a concave function), so every vertical slice of M_rho is one interval whose ends come
   from maximising a concave function of psi over an interval: the unconstrained maximiser is in
   closed form and is clamped to the interval. For each rho and phi the slice length is the length
   of the union of the intervals of the copies k = -1..3. Then
       V = int_3^5 rho int_0^{2 pi} L(rho, phi) dphi drho,
   with composite Gauss-Legendre in s (rho = 4 - cos s, which removes the square-root behaviour at
   rho = 3 and 5) and the midpoint rule in phi. The error is estimated from the same integral at
   half the resolution (the difference, which overestimates the error of the finer one).

2. Monte Carlo over the point-membership test (a cross-check of a different code path). Points are
   drawn in the shell 3 <= rho <= 5, -1 <= z <= 5 pi h + 1 (which contains the swept set) with a
   fixed seed; g is sampled densely in theta (N_THETA samples), every discrete local minimum
   (endpoints included) is refined by safeguarded Newton steps inside its bracket, and the point is
   inside iff the smallest refined value is <= 1.

   The same points are also classified by the slice intervals of part 1, and the number of points on
   which the two classifications disagree is printed (it should be 0: this checks part 1 point by
   point, far more sharply than the Monte Carlo volume does).

Prints both values with their errors; the last line is the reference value and its relative error.
Exits 1 if the two estimates disagree (classification mismatch or more than 4 standard errors).
Usage: /usr/bin/python3 scripts/reference_volume_overlap.py [monte_carlo_points]
           [--distance=R] [--pitch=P] [--turns=N]
The options change the example's centre distance (4), pitch (1.5) and number of turns (2.5), as for
examples/sphere_spring_overlap_close.json (distance 3, pitch 1.7, 3.25 turns); the method needs
neighbouring turns to overlap and at least one and a half turns.
"""
import math
import sys

import numpy as np

R_CENTRE = 4.0           # distance of the ball's centre from the screw axis
PITCH = 1.5              # length per turn
THETA_MAX = 5.0 * math.pi  # 900 degrees
H = PITCH / (2.0 * math.pi)
SEED = 20240601


# ---------------------------------------------------------------- 1. slice integration

def slice_intervals(rho, u):
    """Vertical slice [zlo, zhi] of M_rho at unrolled angle u (arrays broadcast); NaN where empty."""
    c0 = rho * rho + R_CENTRE * R_CENTRE - 1.0          # zeta^2 <= 2 R rho cos(psi) - c0
    a = 2.0 * R_CENTRE * rho
    psi_max = np.arccos(np.clip(c0 / a, -1.0, 1.0))
    lo = np.maximum(-psi_max, u - THETA_MAX)              # feasible psi = u - s, s in [0, THETA_MAX]
    hi = np.minimum(psi_max, u)
    ok = lo <= hi
    # zhi = max over psi of w(psi) + h (u - psi), w = sqrt(a cos psi - c0): w'(psi) = h.
    # zlo = min over psi of -w(psi) + h (u - psi): w'(psi) = -h. With C = cos psi:
    # a^2 (1 - C^2) = 4 h^2 (a C - c0)  ->  a^2 C^2 + 4 h^2 a C - (a^2 + 4 h^2 c0) = 0.
    qa, qb, qc = a * a, 4.0 * H * H * a, -(a * a + 4.0 * H * H * c0)
    C = (-qb + np.sqrt(qb * qb - 4.0 * qa * qc)) / (2.0 * qa)
    psi_star = np.arccos(np.clip(C, -1.0, 1.0))
    psi_star = np.minimum(psi_star, psi_max)

    def w(psi):
        return np.sqrt(np.maximum(a * np.cos(psi) - c0, 0.0))

    p_hi = np.clip(-psi_star, lo, hi)
    p_lo = np.clip(psi_star, lo, hi)
    zhi = w(p_hi) + H * (u - p_hi)
    zlo = -w(p_lo) + H * (u - p_lo)
    return np.where(ok, zlo, np.nan), np.where(ok, zhi, np.nan)


def union_length(zlo, zhi):
    """Length of the union of intervals along the last axis (NaN = empty)."""
    zlo = np.where(np.isnan(zlo), np.inf, zlo)
    zhi = np.where(np.isnan(zhi), -np.inf, zhi)
    order = np.argsort(zlo, axis=-1)
    zlo = np.take_along_axis(zlo, order, axis=-1)
    zhi = np.take_along_axis(zhi, order, axis=-1)
    total = np.zeros(zlo.shape[:-1])
    cur_lo = zlo[..., 0].copy()
    cur_hi = zhi[..., 0].copy()
    for k in range(1, zlo.shape[-1]):
        lo_k, hi_k = zlo[..., k], zhi[..., k]
        gap = lo_k > cur_hi
        total += np.where(gap & np.isfinite(cur_lo), cur_hi - cur_lo, 0.0)
        cur_lo = np.where(gap, lo_k, cur_lo)
        cur_hi = np.where(gap, hi_k, np.maximum(cur_hi, hi_k))
    total += np.where(np.isfinite(cur_lo), cur_hi - cur_lo, 0.0)
    return total


def copies():
    """The k whose copy's u-support [2 pi k - psi_max, 2 pi k + psi_max + THETA_MAX] can meet [0, 2 pi)."""
    return np.arange(-1, int(math.ceil(THETA_MAX / (2.0 * math.pi))) + 2)


def steady_height(rho):
    """Height of a slice of M_rho away from the ends of the helix: the copies k and k + 1 start to
    overlap (a kink of A(rho)) where it equals the pitch."""
    lo, hi = slice_intervals(rho, np.array(2.5 * math.pi))
    return float(hi - lo)


def overlap_onsets():
    """The two radii where steady_height(rho) = PITCH (bisection on each side of R_CENTRE)."""
    out = []
    for a, b in ((R_CENTRE - 1.0 + 1e-12, R_CENTRE), (R_CENTRE, R_CENTRE + 1.0 - 1e-12)):
        fa = steady_height(a) - PITCH
        for _ in range(200):
            m = 0.5 * (a + b)
            fm = steady_height(m) - PITCH
            if (fm > 0) == (fa > 0):
                a, fa = m, fm
            else:
                b = m
        out.append(0.5 * (a + b))
    return out


def slice_volume(n_panels, n_gauss, n_phi):
    """V = int rho A(rho) drho, rho = 4 - cos s, s in [0, pi]: composite Gauss-Legendre in s with
    n_panels panels on each of the three pieces between the overlap onsets, midpoint rule with
    n_phi points in phi."""
    x, wq = np.polynomial.legendre.leggauss(n_gauss)
    breaks = [0.0] + [math.acos(R_CENTRE - r) for r in overlap_onsets()] + [math.pi]
    edges = np.unique(np.concatenate([np.linspace(breaks[i], breaks[i + 1], n_panels + 1)
                                      for i in range(len(breaks) - 1)]))
    s = (0.5 * (edges[:-1, None] + edges[1:, None]) + 0.5 * np.diff(edges)[:, None] * x[None, :]).ravel()
    ws = (0.5 * np.diff(edges)[:, None] * wq[None, :]).ravel()
    rho = R_CENTRE - np.cos(s)
    jac = np.sin(s)
    dphi = 2.0 * math.pi / n_phi
    phi = (np.arange(n_phi) + 0.5) * dphi
    ks = copies()  # copies whose u-support [-psi_max, psi_max + THETA_MAX] meets [0, 2 pi)
    total = 0.0
    for i in range(rho.size):
        u = phi[:, None] + 2.0 * math.pi * ks[None, :]
        zlo, zhi = slice_intervals(rho[i], u)
        area = union_length(zlo, zhi).sum() * dphi       # int L dphi on this cylinder
        total += ws[i] * jac[i] * rho[i] * area
    return total


# ---------------------------------------------------------------- 2. Monte Carlo membership

def g(theta, rho, phi, z):
    return rho * rho + R_CENTRE * R_CENTRE - 2.0 * R_CENTRE * rho * np.cos(phi - theta) + (z - H * theta) ** 2


def min_distance2(rho, phi, z, n_theta):
    """min over theta in [0, THETA_MAX] of g: dense samples, then every discrete local minimum is
    refined by Newton steps clipped to its bracket [theta_{i-1}, theta_{i+1}]."""
    th = np.linspace(0.0, THETA_MAX, n_theta)
    G = g(th[None, :], rho[:, None], phi[:, None], z[:, None])
    left = np.concatenate([np.full((G.shape[0], 1), np.inf), G[:, :-1]], axis=1)
    right = np.concatenate([G[:, 1:], np.full((G.shape[0], 1), np.inf)], axis=1)
    pi_, ii = np.nonzero((G <= left) & (G <= right))
    r, p, zz = rho[pi_], phi[pi_], z[pi_]
    blo = th[np.maximum(ii - 1, 0)]
    bhi = th[np.minimum(ii + 1, n_theta - 1)]
    t = th[ii]
    best = G[pi_, ii]
    for _ in range(8):
        d1 = -2.0 * R_CENTRE * r * np.sin(p - t) - 2.0 * H * (zz - H * t)
        d2 = 2.0 * R_CENTRE * r * np.cos(p - t) + 2.0 * H * H
        step = np.where(d2 > 0, -d1 / np.where(d2 > 0, d2, 1.0), np.where(d1 > 0, blo - t, bhi - t))
        t = np.clip(t + step, blo, bhi)
        best = np.minimum(best, g(t, r, p, zz))
    out = np.full(rho.shape, np.inf)
    np.minimum.at(out, pi_, best)
    return out


def monte_carlo(n_points, n_theta=360, chunk=20000):
    rng = np.random.default_rng(SEED)
    r_lo, r_hi = R_CENTRE - 1.0, R_CENTRE + 1.0
    z_lo, z_hi = -1.0, H * THETA_MAX + 1.0
    box = math.pi * (r_hi ** 2 - r_lo ** 2) * (z_hi - z_lo)
    hits = 0
    disagree = 0
    done = 0
    while done < n_points:
        n = min(chunk, n_points - done)
        rho = np.sqrt(rng.uniform(r_lo ** 2, r_hi ** 2, n))   # uniform in the annulus
        phi = rng.uniform(0.0, 2.0 * math.pi, n)
        z = rng.uniform(z_lo, z_hi, n)
        d2 = min_distance2(rho, phi, z, n_theta)
        inside = d2 <= 1.0
        hits += int(np.count_nonzero(inside))
        # Same points through the slice intervals of part 1; points within 1e-9 of the boundary
        # (in squared distance) may legitimately differ.
        u = phi[:, None] + 2.0 * math.pi * copies()[None, :]
        zlo, zhi = slice_intervals(rho[:, None], u)
        in_slices = np.any((zlo <= z[:, None]) & (z[:, None] <= zhi), axis=1)
        disagree += int(np.count_nonzero((inside != in_slices) & (np.abs(d2 - 1.0) > 1e-9)))
        done += n
    p = hits / n_points
    return box * p, box * math.sqrt(p * (1.0 - p) / n_points), disagree


def main():
    global R_CENTRE, PITCH, THETA_MAX, H
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    for a in sys.argv[1:]:
        if a.startswith("--distance="):
            R_CENTRE = float(a.split("=", 1)[1])
        elif a.startswith("--pitch="):
            PITCH = float(a.split("=", 1)[1])
        elif a.startswith("--turns="):
            THETA_MAX = 2.0 * math.pi * float(a.split("=", 1)[1])
        elif a.startswith("--"):
            print(f"unknown option {a}", file=sys.stderr)
            return 2
    H = PITCH / (2.0 * math.pi)
    n_mc = int(args[0]) if args else 1_000_000
    coarse = slice_volume(n_panels=24, n_gauss=8, n_phi=16384)
    fine = slice_volume(n_panels=48, n_gauss=8, n_phi=32768)
    err = abs(fine - coarse)
    print(f"slice integration: coarse {coarse!r}  fine {fine!r}  |difference| {err:.3g}")
    mc, mc_se, disagree = monte_carlo(n_mc)
    print(f"monte carlo ({n_mc} points, seed {SEED}): {mc:.10g} +- {mc_se:.3g} (standard error, "
          f"relative {mc_se / mc:.3g}), {(mc - fine) / mc_se:+.2f} standard errors from the slice value; "
          f"membership test and slice intervals disagree on {disagree} points")
    no_overlap = math.pi * THETA_MAX / (2.0 * math.pi) * math.hypot(2.0 * math.pi * R_CENTRE, PITCH) + 4.0 / 3.0 * math.pi
    print(f"(without overlap the tube formula would give {no_overlap:.10g})")
    print(f"reference volume {fine!r} relative error {err / fine:.3g}")
    return 0 if disagree == 0 and abs(mc - fine) < 4.0 * mc_se else 1


if __name__ == "__main__":
    sys.exit(main())
