#!/usr/bin/env python3
"""Prints the reference value of validation.yaml: the initial (= conserved total) energy of the elastic gas.

N = 40 spheres, d = 2 mm, rho = 2500 kg/m^3, all with v0 = (0.3, 0.2, 0.1) m/s, no spin and no contact
at t = 0 (as in case.yaml): E = N m |v0|^2 / 2 with m = rho pi d^3 / 6.
"""
import math

n, d, rho = 40, 0.002, 2500.0
v2 = 0.3**2 + 0.2**2 + 0.1**2
m = rho * math.pi * d**3 / 6.0
print(f"{n * 0.5 * m * v2:.12g}")
