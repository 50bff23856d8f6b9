#!/usr/bin/env python3
"""Reference head H(t) of validation/vof_torricelli_slot: a 2D tank of width B draining through a
sharp-edged slot of width b in the middle of its flat floor, quasi-steady Torricelli with the jet's
contraction coefficient of potential flow.

Contraction coefficient: R. von Mises (1917), Berechnung von Ausfluss- und Ueberfallzahlen,
Z. VDI 61, the free-streamline (Kirchhoff) solution of a 2D slot in the end wall of a channel, wall
normal to the axis (theta = 90 deg): C_c = 0.616 at b/B = 0.2 (pi/(pi + 2) = 0.611 for b/B -> 0);
his table is reproduced in hydraulics texts (e.g. Rouse, Elementary Mechanics of Fluids, 1946).

Head balance (Bernoulli from the surface, speed V = q/B, to the vena contracta at p = 0, speed
v_j, with q = C_c b v_j): v_j^2 = 2 g H + V^2, so
    dH/dt = -q/B = -m sqrt(2 g H / (1 - m^2)),  m = C_c b/B,
whose solution is sqrt(H) = sqrt(H0) - m t sqrt(g / (2 (1 - m^2))). Viscosity (C_v ~ 0.98-1 at
these Reynolds numbers, Re = b sqrt(2 g H)/nu > 6000) is left out.
"""
import math

G = 9.81
B = 0.060      # m, tank width (the case simulates half of it, symmetry plane x = 0)
b = 0.012      # m, slot width
CC = 0.616     # von Mises (1917), b/B = 0.2, theta = 90 deg
H0 = 0.060     # m, initial head above the top of the floor plate

m = CC * b / B
k = m * math.sqrt(G / (2.0 * (1.0 - m * m)))

with open("reference.csv", "w") as f:
    f.write("# Quasi-steady Torricelli drain of a 2D tank through a sharp-edged floor slot, b/B = 0.2,\n")
    f.write("# contraction coefficient C_c = 0.616 (von Mises 1917, Kirchhoff free-streamline theory of a\n")
    f.write("# 2D slot in a channel's end wall); dH/dt = -m sqrt(2 g H / (1 - m^2)), m = C_c b/B,\n")
    f.write("# H0 = 60 mm, g = 9.81 m/s^2 (make_reference.py)\n")
    f.write("t [s],H [m]\n")
    for i in range(0, 21):
        t = 0.02 * i
        s = math.sqrt(H0) - k * t
        f.write(f"{t:.2f},{s * s:.9f}\n")
