#!/usr/bin/env python3
"""Reference level and drained mass of validation/vof_bed_drain: a 2D tank of width B draining
through a sharp-edged slot of width b in the middle of its floor plate, after the water has passed
a fixed bed of spheres held between a grid and a plate, quasi-steady head balance integrated in time.

Head balance between the free surface (level y, at rest, p = 0) and the jet's vena contracta below
the slot (p = 0), with the superficial velocity U = q/B of the tank (q the volume flow per depth):

    rho g H = rho v_j^2 (1 - m^2)/2 + L_w (A U + C U^2),   v_j = U/m,   m = C_c b/B,

* H = y - y_plate, the level above the top of the floor plate (as validation/vof_torricelli_slot);
* the orifice: Torricelli with the contraction coefficient of potential flow, C_c = 0.616 for a 2D
  slot in a channel's end wall at b/B = 0.2 (R. von Mises 1917, Z. VDI 61; the coefficient of
  validation/vof_torricelli_slot);
* the bed: Ergun (1952), A = 150 mu (1 - eps)^2/(eps^3 d^2), C = 1.75 rho (1 - eps)/(eps^3 d) (seed
  001 eq. 35; Gidaspow's drag law of the run is Ergun's for eps < 0.8), at the simple-cubic lattice's
  eps = 1 - pi/6 (the run's bed: cell layers of 2 x 2 spheres hold exactly this eps, and the spheres
  stay within 0.05 mm of their lattice places), over the wetted length L_w = min(max(y - y_bed0, 0),
  y_bed1 - y_bed0);
* the level falls at U above and below the bed and at U/eps inside it.

The quadratic for U is solved at every stage of a classical RK4 step (dt = 0.1 ms). The drained mass
is rho times the volume per depth between the initial and the current level (the bed's pore volume
inside it), here per initial mass: all of the water lies above the outlet.
"""
import math

G = 9.81
RHO, MU = 1000.0, 1.0e-3          # water, seed 002 Table 2
B, b = 0.060, 0.012               # m, tank and slot width (the case simulates half of both)
CC = 0.616                        # von Mises (1917), b/B = 0.2
D = 1.0e-3                        # m, sphere diameter
EPS = 1.0 - math.pi / 6.0         # simple-cubic lattice of touching spheres
Y_PLATE = 0.022                   # m, top of the floor plate
Y_BED0, Y_BED1 = 0.032, 0.052     # m, the grid and the hold-down plate (bed 20 mm high)
Y0 = 0.092                        # m, initial level

m = CC * b / B
A = 150.0 * MU * (1.0 - EPS) ** 2 / (EPS ** 3 * D * D)
C = 1.75 * RHO * (1.0 - EPS) / (EPS ** 3 * D)


def superficial_velocity(y):
    head = y - Y_PLATE
    if head <= 0.0:
        return 0.0
    lw = min(max(y - Y_BED0, 0.0), Y_BED1 - Y_BED0)
    qa = RHO * (1.0 - m * m) / (2.0 * m * m) + lw * C
    qb = lw * A
    return (-qb + math.sqrt(qb * qb + 4.0 * qa * RHO * G * head)) / (2.0 * qa)


def level_rate(y):
    u = superficial_velocity(y)
    return -(u / EPS if Y_BED0 < y <= Y_BED1 else u)


def water_above_plate(y):
    """Water volume per unit area of the tank between the plate's top and level y."""
    total = 0.0
    for lo, hi, e in ((Y_PLATE, Y_BED0, 1.0), (Y_BED0, Y_BED1, EPS), (Y_BED1, 1.0, 1.0)):
        top = min(y, hi)
        if top > lo:
            total += (top - lo) * e
    return total


dt, t_end, every = 1.0e-4, 1.8, 200     # samples every 0.02 s, until the model has drained 98 %
v0 = water_above_plate(Y0)
rows = []
y = Y0
for i in range(int(round(t_end / dt)) + 1):
    if i % every == 0:
        rows.append((i * dt, max(y - Y_PLATE, 0.0), (v0 - water_above_plate(y)) / v0))
    k1 = level_rate(y)
    k2 = level_rate(y + 0.5 * dt * k1)
    k3 = level_rate(y + 0.5 * dt * k2)
    k4 = level_rate(y + dt * k3)
    y += dt * (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0

with open("reference.csv", "w") as f:
    f.write("# Quasi-steady drain of a 2D tank through a bed of 1 mm spheres (simple-cubic lattice, eps = 1 - pi/6,\n")
    f.write("# 20 mm high, 10 mm above the floor plate) and a sharp-edged floor slot, b/B = 0.2:\n")
    f.write("# rho g H = rho v_j^2 (1 - m^2)/2 + L_w (A U + C U^2), m = C_c b/B, C_c = 0.616 (von Mises 1917),\n")
    f.write("# A, C of Ergun (1952), the level falling at U outside the bed and U/eps inside it; RK4, dt = 0.1 ms.\n")
    f.write("# H: level above the top of the floor plate; drained: drained mass / initial water mass (make_reference.py)\n")
    f.write("t [s],H [m],drained [-]\n")
    for t, h, v in rows:
        f.write(f"{t:.2f},{h:.9f},{v:.9f}\n")
