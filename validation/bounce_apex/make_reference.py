#!/usr/bin/env python3
"""Writes reference.csv: rebound apex ratio (z_apex - r)/(z0 - r) = e^2 for a sphere dropped from rest.

Impact speed v = sqrt(2 g h0), rebound speed e v, apex height h1 = (e v)^2/(2 g) = e^2 h0 (energy
conservation in flight; neglects gravity during the ~0.5 ms contact and the overlap at contact onset,
both below 1 % here).
"""
with open("reference.csv", "w") as f:
    f.write("# Rebound apex ratio h1/h0 = e^2 (definition of e + free flight); written by make_reference.py\n")
    f.write("e [-],apex_ratio [-]\n")
    for i in range(0, 21):
        e = 0.05 * i
        f.write(f"{e:.2f},{e * e:.6g}\n")
