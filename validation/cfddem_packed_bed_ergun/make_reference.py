#!/usr/bin/env python3
"""Ergun (1952) pressure drop of the fixed bed of case.yaml (seed 001 eq. 35):
dp = 150 (1-eps)^2 mu U Hb / (eps^3 d^2) + 1.75 (1-eps) rho U^2 Hb / (eps^3 d)."""
import math

eps = 1.0 - math.pi / 6.0       # touching simple-cubic lattice
d, Hb = 0.002, 0.032            # m
mu, rho = 1.0e-3, 1000.0        # Pa s, kg/m^3
with open("reference.csv", "w") as f:
    f.write("# Ergun (1952) equation, seed 001 eq. 35, for eps = 1 - pi/6, d = 2 mm, Hb = 32 mm, water\n")
    f.write("# computed by make_reference.py\n")
    f.write("U [m/s],dp [Pa]\n")
    for U in [0.002, 0.005, 0.01, 0.02, 0.04]:
        dp = 150 * (1 - eps) ** 2 * mu * U * Hb / (eps ** 3 * d ** 2) + 1.75 * (1 - eps) * rho * U ** 2 * Hb / (eps ** 3 * d)
        f.write(f"{U},{dp:.10g}\n")
