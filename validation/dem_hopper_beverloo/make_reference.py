#!/usr/bin/env python3
"""Prints the reference value of validation.yaml: Beverloo's discharge rate of the silo in case.yaml.

W = C rho_b sqrt(g) (D - k d)^(5/2), C = 0.58, k = 1.5 (Beverloo, Leniger & van de Velde 1961,
Chem. Eng. Sci. 15, 260-269; Nedderman 1992, Statics and Kinematics of Granular Materials, ch. 10).
Bulk density rho_b: of this case's settled bed before the plug opens. Its mean centre height at
t = 0.29 s (bed monitor, column mean_centre_height) is 17.91 mm, so the bed is H = 2 x 17.91 mm high
and rho_b = N m / (pi R^2 H) (N = 4000, d = 3 mm, rho = 2500 kg/m^3, silo radius R = 30 mm).
"""
import math

n, d, rho, silo_radius, orifice, g = 4000, 0.003, 2500.0, 0.03, 0.021, 9.81
mean_centre_height = 0.01791
bed_mass = n * rho * math.pi * d**3 / 6.0
rho_b = bed_mass / (math.pi * silo_radius**2 * 2.0 * mean_centre_height)
w = 0.58 * rho_b * math.sqrt(g) * (orifice - 1.5 * d) ** 2.5
print(f"bulk density {rho_b:.1f} kg/m^3 (solid fraction {rho_b / rho:.3f}), Beverloo W = {w:.6g} kg/s")
