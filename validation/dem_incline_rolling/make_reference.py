#!/usr/bin/env python3
"""Writes reference.csv: acceleration of a sphere released on an incline of angle theta = 30 deg vs friction mu.

Rolling without slip (tan(theta) <= 3.5 mu, solid sphere I = 2/5 m R^2): a = (5/7) g sin(theta);
sliding (tan(theta) > 3.5 mu): a = g (sin(theta) - mu cos(theta)).
"""
import math

g, theta = 9.81, math.radians(30.0)
mus = [0.02, 0.05, 0.1, 0.15, 0.2, 0.3, 0.5]


def acceleration(mu):
    if math.tan(theta) <= 3.5 * mu:
        return 5.0 / 7.0 * g * math.sin(theta)
    return g * (math.sin(theta) - mu * math.cos(theta))


with open("reference.csv", "w") as f:
    f.write("# Sphere on an incline (rigid-body mechanics, e.g. Goldstein, Classical Mechanics; Landau-Lifshitz Vol. 1):\n")
    f.write("# rolling a = 5/7 g sin(theta) if tan(theta) <= 3.5 mu, sliding a = g (sin(theta) - mu cos(theta)) otherwise\n")
    f.write("# theta = 30 deg, g = 9.81 m/s^2 (as in case.yaml); the regimes change at mu = tan(30 deg)/3.5 = 0.165;\n")
    f.write("# written by make_reference.py\n")
    f.write("mu [-],a [m/s^2]\n")
    for mu in mus:
        f.write(f"{mu:g},{acceleration(mu):.12g}\n")
