#!/usr/bin/env python3
"""Writes reference.csv: rebound of an elastic sphere after an oblique impact on a wall (no initial spin).

Linear normal and tangential springs with k_t / k_n = 2/7, no damping (e = 1), Coulomb limit mu:
the contact-point velocity u_c = v_t - w R obeys du_c/dt = -3.5 F_t / m (solid sphere, I = 2/5 m R^2),
so it oscillates with the normal period. While the contact sticks F_t / F_n = (2/7) u_c0 / v_n is
constant (both grow as sin(w t)); hence (Thornton et al. 2013, Powder Technol. 233, 30-46, sec. 3;
Maw, Barber & Fawcett 1976 for the general elastic case)
  sticking, v_t <= 3.5 mu v_n:  u_c reverses, u_c' = -v_t:  v_t' = 3/7 v_t,       w' R = 10/7 v_t;
  sliding,  v_t >  3.5 mu v_n:  impulse mu (1 + e) m v_n:  v_t' = v_t - 2 mu v_n, w' R = 5 mu v_n.
"""
mu, vn = 0.5, 0.2
swept = [0.02, 0.05, 0.1, 0.2, 0.3, 0.35, 0.4, 0.5, 0.7, 1.0]
limit = 3.5 * mu * vn
grid = sorted(set(swept + [round(0.01 * i, 10) for i in range(1, 101)] + [limit]))


def rebound(vt):
    if vt <= limit:
        jt = 4.0 / 7.0 * vt          # tangential impulse / m = (2/7) (u_c0 - u_c')
    else:
        jt = 2.0 * mu * vn           # mu (1 + e) v_n, e = 1
    return vt - jt, 2.5 * jt         # v_t', w' R


with open("reference.csv", "w") as f:
    f.write("# Oblique impact of an elastic sphere on a wall, linear springs k_t/k_n = 2/7, e = 1, mu = 0.5, v_n = 0.2 m/s:\n")
    f.write("# sticking (v_t <= 3.5 mu v_n = 0.35 m/s): v_t' = 3/7 v_t, w'R = 10/7 v_t; sliding: v_t' = v_t - 2 mu v_n, w'R = 5 mu v_n\n")
    f.write("# (Thornton, Cummins & Cleary 2013, Powder Technol. 233, 30-46, sec. 3; Maw, Barber & Fawcett 1976); written by make_reference.py\n")
    f.write("vt [m/s],vt_rebound [m/s],spin_R [m/s]\n")
    for vt in grid:
        a, b = rebound(vt)
        f.write(f"{vt:.10g},{a:.12g},{b:.12g}\n")
