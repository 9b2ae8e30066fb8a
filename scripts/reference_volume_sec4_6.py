#!/usr/bin/env python3
"""Independent reference volumes for section 4.6 of 000_0a5975c48c1ac19b.txt: a hemispherical shell of
radius 5 (its rim at d, its apex at d + 5 along its axis) extruded by the prismatic joint over
d in [15, 15 + s], turned by joint 2 about an axis through O (the origin of frame 1) perpendicular to
its own axis, then turned a whole turn by joint 1 about an axis through O perpendicular to joint 2's.

The extruded shell is a body of revolution about its axis: a point at distance L from O and axial
coordinate t lies in it when r = sqrt(L^2 - t^2) <= 5 and 15 <= g <= 15 + s, g = t - sqrt(25 - r^2)
(the dome through the point has its rim at g). On the sphere |x - O| = L, g runs from L - 5 (on
the axis) to sqrt(L^2 - 25) (at r = 5), decreasing in t: the admissible t form one interval
[t_lo, t_hi], t_k = (k^2 + L^2 - 25) / (2 k) where g = k is reached.

Joint 2 turns the shell's axis through directions whose angle from joint 1's axis covers
[0, a_max] (a_max = 135 deg for the range [-45, 225] deg: cos a = sin q2); joint 1 then turns
every direction about that axis. A point at distance L and angle c from joint 1's axis is reached
when some such direction e has L cos(angle(x, e)) in [t_lo, t_hi]; the angles reachable are
[max(0, c - a_max), ...] and the largest cosine decides: c <= a_max + acos(t_lo / L). So

    V = 2 pi int L^2 (1 - cos min(pi, a_max + acos(t_lo(L) / L))) dL

over the L where [t_lo, t_hi] is not empty. Run with /usr/bin/python3 (scipy from Debian); prints
a_max in degrees, the stroke s and V.
"""
import math
from scipy.integrate import quad


def t_interval(L, s):
    k1, k2 = 15.0, 15.0 + s
    gmin, gmax = L - 5, math.sqrt(max(L * L - 25, 0.0))
    if k2 < gmin or k1 > gmax:
        return None
    t_lo = (k2 * k2 + L * L - 25) / (2 * k2) if k2 <= gmax else gmax  # g <= k2
    t_hi = (k1 * k1 + L * L - 25) / (2 * k1) if k1 >= gmin else L  # g >= k1
    return t_lo, t_hi


def volume(a_max, s):
    def f(L):
        iv = t_interval(L, s)
        if iv is None:
            return 0.0
        gam = min(math.pi, a_max + math.acos(min(1.0, iv[0] / L)))
        return L * L * (1 - math.cos(gam))
    lo, hi = math.sqrt(250.0), 20.0 + s
    cuts = sorted({lo, hi, 20.0, math.sqrt((15 + s) ** 2 + 25)})
    cuts = [c for c in cuts if lo <= c <= hi]
    total = 0.0
    for a, b in zip(cuts, cuts[1:]):
        # L = b - u^2 removes the square-root behaviour of acos at the top end
        v, _ = quad(lambda u: f(b - u * u) * 2 * u, 0, math.sqrt(b - a), epsabs=0, epsrel=1e-13, limit=400)
        total += v
    return 2 * math.pi * total


if __name__ == "__main__":
    for a_deg, s in ((135, 5), (90, 5), (135, 3)):
        print(a_deg, s, repr(volume(math.radians(a_deg), s)))
