#!/usr/bin/env python3
"""Terminal velocity of a 2 mm sphere (2500 kg/m^3) in a liquid of 1000 kg/m^3 with the
Schiller-Naumann drag law (f = 1 + 0.15 Re^0.687), for viscosities chosen to give Re_t = 0.1, 1,
10, 100, 500: mu = sqrt(rho d^3 (rho_p - rho) g / (18 Re f(Re))), v_t = Re mu / (rho d)."""
import math

d, rho_p, rho, g = 2.0e-3, 2500.0, 1000.0, 9.81
with open("reference.csv", "w") as out:
    out.write("# Terminal velocity with the Schiller & Naumann (1933) drag law; computed by make_reference.py\n")
    out.write("mu [Pa s],Re_t [-],v_t [m/s]\n")
    rows = []
    for re in [0.1, 1.0, 10.0, 100.0, 500.0]:
        f = 1 + 0.15 * re ** 0.687
        mu = float(f"{math.sqrt(rho * d ** 3 * (rho_p - rho) * g / (18 * re * f)):.6g}")
        v = d * d * (rho_p - rho) * g / (18 * mu)  # re-solve with the rounded mu
        for _ in range(200):
            r = rho * v * d / mu
            v = d * d * (rho_p - rho) * g / (18 * mu * (1 + 0.15 * r ** 0.687))
        rows.append((mu, rho * v * d / mu, v))
    for mu, r, v in sorted(rows):
        out.write(f"{mu:.6g},{r:.6g},{v:.10g}\n")
