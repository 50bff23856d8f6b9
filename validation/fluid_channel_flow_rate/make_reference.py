#!/usr/bin/env python3
"""Prints the reference values of validation.yaml: plane Poiseuille flow at an imposed bulk velocity U
needs the driving gradient G = -dp/dx = 12 mu U / H^2 (White, Viscous Fluid Flow, 3rd ed., eq. 3-42),
and carries Q = U H W, with U = 0.3 m/s, mu = 0.5 Pa s, H = 1 m, channel depth W = 0.1 m (case.yaml).
The discrete bulk velocity (midpoint sum over 16 cells) of the exact parabola is G/(2 mu) (H^2/6 + h^2/12),
so the controller finds G_h = 12 mu U / (H^2 + h^2 / 2), -0.195 % from G at h = H/16."""
U, mu, H, W, h = 0.3, 0.5, 1.0, 0.1, 1.0 / 16
print(f"G = {12 * mu * U / H**2:.12g} Pa/m")
print(f"G_h = {12 * mu * U / (H**2 + h**2 / 2):.12g} Pa/m")
print(f"Q = {U * H * W:.12g} m^3/s")
