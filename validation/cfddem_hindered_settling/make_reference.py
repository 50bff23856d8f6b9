#!/usr/bin/env python3
"""Richardson & Zaki (1954) hindered settling velocity v = v_t eps^n for the suspension of case.yaml
(d = 1 mm, rho_p = 2500, rho_f = 1200 kg/m^3, mu = 0.1 Pa s), at the lattice spacings of the sweep.
v_t: terminal velocity of the single sphere with the drag law of the case at eps = 1 (di_felice ->
Dallavalle, f = (0.63 sqrt(Re) + 4.8)^2 / 24, seed 001 eq. 15); n from Rowe (1987):
n = (4.7 + 0.41 Re_t^0.75) / (1 + 0.175 Re_t^0.75)."""
import math

d, rho_p, rho_f, mu, g = 1.0e-3, 2500.0, 1200.0, 0.1, 9.81
v = d * d * (rho_p - rho_f) * g / (18 * mu)  # Stokes start
for _ in range(200):  # 18 mu f(Re) v = d^2 (rho_p - rho_f) g
    re = rho_f * v * d / mu
    f = (0.63 * math.sqrt(re) + 4.8) ** 2 / 24
    v = d * d * (rho_p - rho_f) * g / (18 * mu * f)
re_t = rho_f * v * d / mu
n = (4.7 + 0.41 * re_t ** 0.75) / (1 + 0.175 * re_t ** 0.75)
with open("reference.csv", "w") as out:
    out.write("# Richardson & Zaki (1954) v = v_t eps^n, n of Rowe (1987); computed by make_reference.py\n")
    out.write(f"# v_t = {v:.6g} m/s (Dallavalle drag), Re_t = {re_t:.4g}, n = {n:.4f}\n")
    out.write("spacing [m],eps [-],v [m/s]\n")
    for phi in [0.4, 0.3, 0.2, 0.1, 0.05]:
        s = d * (math.pi / (6 * phi)) ** (1 / 3)
        out.write(f"{s:.7g},{1 - phi:.4f},{v * (1 - phi) ** n:.10g}\n")
