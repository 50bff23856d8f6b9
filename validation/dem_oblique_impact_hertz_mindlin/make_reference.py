#!/usr/bin/env python3
"""Writes reference.csv: rebound of an elastic sphere (e = 1) after an oblique impact in the gross-sliding
regime (Maw, Barber & Fawcett 1976: for large normalised incidence the contact slides throughout), no
initial spin: the tangential impulse is mu (1 + e) m v_n, so
  v_t' = v_t - 2 mu v_n,   w' R = 5 mu v_n   (solid sphere, I = 2/5 m R^2).
"""
mu, vn = 0.2, 0.3
swept = [0.4, 0.5, 0.7, 1.0, 1.5]
with open("reference.csv", "w") as f:
    f.write("# Oblique impact, gross sliding (Maw, Barber & Fawcett 1976, Wear 38, 101; Thornton, Cummins & Cleary 2013,\n")
    f.write("# Powder Technol. 233, 30-46): impulse mu (1 + e) m v_n with e = 1, mu = 0.2, v_n = 0.3 m/s:\n")
    f.write("# v_t' = v_t - 2 mu v_n, w'R = 5 mu v_n; written by make_reference.py\n")
    f.write("vt [m/s],vt_rebound [m/s],spin_R [m/s]\n")
    for vt in swept:
        f.write(f"{vt:g},{vt - 2 * mu * vn:.12g},{5 * mu * vn:.12g}\n")
