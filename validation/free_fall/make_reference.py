#!/usr/bin/env python3
"""Writes reference.csv: free flight z(t) = z0 + v0 t - g t^2/2, vz(t) = v0 - g t (z0 = 0.9 m, v0 = 1 m/s, g = 9.81 m/s^2)."""
z0, v0, g = 0.9, 1.0, 9.81
with open("reference.csv", "w") as f:
    f.write("# Analytic free flight (constant gravity, no drag): z = z0 + v0 t - g t^2/2, vz = v0 - g t\n")
    f.write("# z0 = 0.9 m, v0 = 1.0 m/s, g = 9.81 m/s^2 (as in case.yaml); written by make_reference.py\n")
    f.write("t [s],z [m],vz [m/s]\n")
    for i in range(0, 41, 2):
        t = 0.01 * i
        f.write(f"{t:.2f},{z0 + v0 * t - 0.5 * g * t * t:.12g},{v0 - g * t:.12g}\n")
