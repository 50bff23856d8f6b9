#!/usr/bin/env python3
"""Writes reference.csv: the height at which a bead of density rho_p floats in case.yaml.

The unresolved coupling gives a bead the force -V grad p at its centre, with grad p the cell-centred
gradient of the mixture's pressure interpolated linearly (trilinear sampling; the gradient varies
along z only). At rest the pressure is hydrostatic: between the centres of two cells it changes by
rho_f g h with the face density rho_f = (rho_L + rho_R)/2 (fluid/variable_density.hpp), so the
central difference at a cell centre is g times the mean of the two face densities around it. With
water (1000 kg/m^3) below the face z = 40 mm and air (1 kg/m^3) above, on 5 mm cells:

    centre z [mm]   32.5    37.5      42.5     47.5
    dp/dz / g       1000    750.25    250.75   1

The bead floats where -dp/dz = rho_p g: linear interpolation of that table (the bead's own void
fraction, 3 % of a cell, and the interface's small motion are neglected)."""
rho_w, rho_a, h, face = 1000.0, 1.0, 0.005, 0.040
rf = 0.5 * (rho_w + rho_a)
table = [(face - 1.5 * h, rho_w), (face - 0.5 * h, 0.5 * (rho_w + rf)), (face + 0.5 * h, 0.5 * (rf + rho_a)),
         (face + 1.5 * h, rho_a)]


def height(rho_p):
    for (z0, g0), (z1, g1) in zip(table, table[1:]):
        if g1 <= rho_p <= g0:
            return z0 + (g0 - rho_p) / (g0 - g1) * (z1 - z0)
    raise ValueError(rho_p)


with open("reference.csv", "w") as f:
    f.write("# Equilibrium height of a floating bead: -dp/dz = rho_p g with the discrete hydrostatic pressure\n")
    f.write("# of water under air on 5 mm cells, interface on the face z = 40 mm (make_reference.py)\n")
    f.write("rho_p [kg/m^3],z [m]\n")
    for rho_p in (250.0, 500.0, 750.0):
        f.write(f"{rho_p:g},{height(rho_p):.6f}\n")
