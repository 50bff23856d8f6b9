#!/usr/bin/env python3
"""Writes reference.csv: c(y, t) = erfc(y / (2 sqrt(D t))), the scalar diffusing from a wall held at 1
into a semi-infinite medium at 0 (Carslaw & Jaeger, Conduction of Heat in Solids, 2nd ed., sec. 2.4,
eq. 2.4(3); Crank, The Mathematics of Diffusion, eq. 3.13), D = 0.01 m^2/s, at the two probe cells
y = 2.5/64 m and 9.5/64 m of case.yaml."""
from math import erfc, sqrt

D = 0.01
ys = {"c_near": 2.5 / 64, "c_far": 9.5 / 64}
with open("reference.csv", "w") as f:
    f.write("# c(y, t) = erfc(y / (2 sqrt(D t))), D = 0.01 m^2/s, y_near = 0.0390625 m, y_far = 0.1484375 m\n")
    f.write("# Carslaw & Jaeger (1959) sec. 2.4 eq. (3); computed by make_reference.py\n")
    f.write("t [s],c_near [-],c_far [-]\n")
    for k in range(1, 11):
        t = 0.1 * k
        f.write(f"{t:.12g},{erfc(ys['c_near'] / (2 * sqrt(D * t))):.12g},{erfc(ys['c_far'] / (2 * sqrt(D * t))):.12g}\n")
