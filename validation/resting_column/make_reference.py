#!/usr/bin/env python3
"""Writes reference.csv: static compression of a column of N equal spheres on a rigid floor.

Hertz: F = 4/3 E* sqrt(R* delta) delta  ->  delta = (3 F / (4 E* sqrt(R*)))^(2/3)
(Johnson, Contact Mechanics, 1985, eq. 4.22-4.23). Sphere-floor contact carries N m g with
E* = E/(1-nu^2), R* = r; the contact between spheres k and k+1 (k = 1..N-1 from the bottom)
carries (N-k) m g with E* = E/(2(1-nu^2)), R* = r/2. Compression = (N-1) d + r - z_top,
the sum of all overlaps.
"""
import math

N, rho, d, nu, g = 10, 2500.0, 0.004, 0.3, 9.81
r = d / 2
m = rho * math.pi / 6 * d ** 3


def overlap(force, e_star, r_star):
    return (3 * force / (4 * e_star * math.sqrt(r_star))) ** (2 / 3)


def compression(E):
    total = overlap(N * m * g, E / (1 - nu ** 2), r)
    for k in range(1, N):
        total += overlap((N - k) * m * g, E / (2 * (1 - nu ** 2)), r / 2)
    return total


moduli = sorted(set([1e7, 3e7, 1e8] + [10 ** (5.8 + 0.1 * k) for k in range(25)]))
with open("reference.csv", "w") as f:
    f.write("# Static Hertz compression of a column of 10 spheres (d = 4 mm, rho = 2500 kg/m^3, nu = 0.3, g = 9.81 m/s^2)\n")
    f.write("# on a rigid floor: sum of the overlaps delta = (3F/(4 E* sqrt(R*)))^(2/3) (Johnson 1985, eq. 4.22-4.23)\n")
    f.write("# written by make_reference.py\n")
    f.write("E [Pa],compression [m]\n")
    for E in moduli:
        f.write(f"{E:.10g},{compression(E):.10g}\n")
