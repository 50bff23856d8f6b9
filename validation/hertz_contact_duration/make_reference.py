#!/usr/bin/env python3
"""Writes reference.csv: elastic Hertz contact duration of a sphere on a rigid plane.

t_c = 2.8683 (m^2 / (R E*^2 v))^(1/5)  (Johnson, Contact Mechanics, 1985, sec. 11.4, eq. 11.24:
t_c = 2.94 delta*/v with delta* = (15 m v^2 / (16 E* R^(1/2)))^(2/5); 2.94 is 2 * 1.4716, and
2 * 1.4716 * (15/16)^(2/5) = 2.8683). E* = E/(1 - nu^2) for a rigid wall, R = sphere radius.
"""
import math

rho, d, E, nu = 2500.0, 0.004, 5.0e6, 0.3
r = d / 2
m = rho * math.pi / 6 * d ** 3
Es = E / (1 - nu ** 2)
integral = 1.4716  # int_0^1 dx / sqrt(1 - x^(5/2)), Johnson eq. 11.24
coefficient = 2 * integral * (15 / 16) ** 0.4


def tc(v):
    return coefficient * (m * m / (r * Es * Es * v)) ** 0.2


speeds = sorted(set([0.1, 0.3, 1.0, 3.0] + [0.08 * 1.2 ** k for k in range(21)]))
with open("reference.csv", "w") as f:
    f.write("# Elastic Hertz contact duration, sphere on a rigid plane (Johnson 1985, eq. 11.24):\n")
    f.write(f"# t_c = {coefficient:.5f} (m^2/(R E*^2 v))^(1/5), m = {m:.6g} kg, R = {r} m, E* = E/(1-nu^2) = {Es:.6g} Pa\n")
    f.write("# written by make_reference.py\n")
    f.write("v [m/s],t_contact [s]\n")
    for v in speeds:
        f.write(f"{v:.10g},{tc(v):.10g}\n")
