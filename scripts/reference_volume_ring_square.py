#!/usr/bin/env python3
"""Independent reference volume, without any B-rep, for a prism whose section is the square
[-1, 1]^2 less the disk of radius R about the origin (tests/util/box_hole.hpp's box with its hole,
extruded along z to height H), turned by an angle A about the line x = C, y = 0 parallel to z
(C > 1: the axis is outside the square).

Every section z = const of the swept set is the region the planar section sweeps turning about
(C, 0): on the circle of radius r about that point, the section covers a union I(r) of arcs whose
ends are where the circle crosses the square's sides and the disk's rim (found in closed form),
and the turn covers I(r) + [0, A]. So

    volume = H * int r |I(r) + [0, A]| dr,   r from C - 1 to hypot(C + 1, 1)

integrated by composite Gauss-Legendre; the printed error estimate is the change from halving the
panels. Run with python3 (no other package):

    reference_volume_ring_square.py C R H A_degrees

prints the volume and its error estimate.
"""
import math
import sys


def gauss_legendre(n):
    xs, ws = [], []
    for i in range(1, n + 1):
        x = math.cos(math.pi * (i - 0.25) / (n + 0.5))
        for _ in range(100):
            p0, p1 = 1.0, x
            for k in range(2, n + 1):
                p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
            dp = n * (x * p1 - p0) / (x * x - 1)
            step = p1 / dp
            x -= step
            if abs(step) < 1e-16:
                break
        xs.append(x)
        ws.append(2 / ((1 - x * x) * dp * dp))
    return xs, ws


def in_section(x, y, R):
    return abs(x) <= 1 and abs(y) <= 1 and x * x + y * y >= R * R


def covered(r, C, R, A):
    """The measure of I(r) + [0, A] on the circle of radius r about (C, 0)."""
    two_pi = 2 * math.pi
    ends = [0.0]
    for v in (-1.0, 1.0):
        cx = (v - C) / r  # the circle meets x = v
        if abs(cx) <= 1:
            a = math.acos(cx)
            ends += [a, two_pi - a]
        sy = v / r  # the circle meets y = v
        if abs(sy) <= 1:
            a = math.asin(sy)
            ends += [a % two_pi, (math.pi - a) % two_pi]
    cc = (R * R - C * C - r * r) / (2 * C * r)  # the circle meets the disk's rim
    if abs(cc) <= 1:
        a = math.acos(cc)
        ends += [a, two_pi - a]
    ends = sorted(set(ends)) + [two_pi]
    arcs = []
    for a, b in zip(ends[:-1], ends[1:]):
        m = 0.5 * (a + b)
        if b > a and in_section(C + r * math.cos(m), r * math.sin(m), R):
            arcs += [(a, b + A), (a - two_pi, b + A - two_pi)]
    arcs.sort()
    total, cur = 0.0, None
    for a, b in arcs:
        if cur is not None and a <= cur[1]:
            cur[1] = max(cur[1], b)
            continue
        if cur is not None:
            total += max(0.0, min(cur[1], two_pi) - max(cur[0], 0.0))
        cur = [a, b]
    if cur is not None:
        total += max(0.0, min(cur[1], two_pi) - max(cur[0], 0.0))
    return min(total, two_pi)


def area(C, R, A, panels):
    lo, hi = C - 1, math.hypot(C + 1, 1)
    xs, ws = gauss_legendre(8)
    total = 0.0
    for k in range(panels):
        a, b = lo + (hi - lo) * k / panels, lo + (hi - lo) * (k + 1) / panels
        for x, w in zip(xs, ws):
            r = 0.5 * (a + b) + 0.5 * (b - a) * x
            total += 0.5 * (b - a) * w * r * covered(r, C, R, A)
    return total


def main():
    C, R, H, A = (float(v) for v in sys.argv[1:5])
    assert C > 1 and 0 < R < 1
    A = math.radians(A)
    coarse, fine = area(C, R, A, 2000), area(C, R, A, 4000)
    print(f"{H * fine:.12f} +- {H * abs(fine - coarse):.1e}")


if __name__ == "__main__":
    main()
