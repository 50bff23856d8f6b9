#!/usr/bin/env python3
"""Writes reference.csv: contact duration of a linear spring-dashpot impact on a rigid plane.

The overlap obeys m x'' + c x' + k x = 0 (seed 000 Appendix B eq. B.5), a damped oscillator that
leaves contact after half a damped period: t_c = pi / (w0 sqrt(1 - zeta^2)), w0 = sqrt(k/m). The
damping ratio that gives restitution e is zeta = -ln e / sqrt(pi^2 + ln^2 e) (e = exp(-pi zeta /
sqrt(1 - zeta^2))), so t_c = sqrt(m/k) sqrt(pi^2 + ln^2 e), independent of the impact velocity.
"""
import math

rho, d, k = 2500.0, 0.004, 1000.0
m = rho * math.pi / 6 * d ** 3


def tc(e):
    return math.sqrt(m / k) * math.sqrt(math.pi ** 2 + math.log(e) ** 2)


values = sorted(set([0.3, 0.5, 0.7, 0.9, 1.0] + [0.25 + 0.025 * i for i in range(31)]))
with open("reference.csv", "w") as f:
    f.write("# Linear spring-dashpot contact duration, sphere on a rigid plane: half a damped period,\n")
    f.write(f"# t_c = sqrt(m/k) sqrt(pi^2 + ln^2 e), m = {m:.6g} kg, k = {k} N/m (seed 000 App. B eq. B.5)\n")
    f.write("# written by make_reference.py\n")
    f.write("e [-],t_contact [s]\n")
    for e in values:
        f.write(f"{e:.10g},{tc(e):.10g}\n")
