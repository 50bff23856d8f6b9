#!/usr/bin/env python3
"""Prints the reference of validation.yaml: steady 1D flow at superficial velocity U through a medium
of void fraction eps with linear drag K (u_f - 0) per volume, model A (seed 000 eq. 5.7):
-eps dp/dx = K u_f, u_f = U / eps  ->  -dp/dx = K U / eps^2. Simple-cubic lattice of touching spheres:
eps = 1 - pi/6, n = 1/d^3 spheres per volume, Stokes drag K = n 3 pi mu d; d = 2 mm, mu = 1e-3 Pa s,
U = 10 mm/s (case.yaml)."""
from math import pi

d, mu, U = 0.002, 1.0e-3, 0.01
eps = 1.0 - pi / 6.0
K = 3.0 * pi * mu * d / d**3
print(f"eps = {eps:.12g}, K = {K:.12g} kg/(m^3 s)")
print(f"-dp/dx = {K * U / eps**2:.12g} Pa/m")
print(f"dp over L = 20 mm = {K * U / eps**2 * 0.02:.12g} Pa")
