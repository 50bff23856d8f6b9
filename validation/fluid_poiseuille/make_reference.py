#!/usr/bin/env python3
"""Prints the reference values of validation.yaml: plane Poiseuille flow u(y) = G y (H - y) / (2 mu),
flow rate Q = G H^3 W / (12 mu) (White, Viscous Fluid Flow, 3rd ed., eq. 3-42), with G = 3 Pa/m,
mu = 0.5 Pa s, H = 1 m, channel depth W = 0.1 m (as in case.yaml)."""
G, mu, H, W = 3.0, 0.5, 1.0, 0.1
for y in (0.03125, 0.28125, 0.46875):
    print(f"u({y}) = {G * y * (H - y) / (2 * mu):.12g} m/s")
print(f"Q = {G * H**3 * W / (12 * mu):.12g} m^3/s")
