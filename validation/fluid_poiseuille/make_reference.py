#!/usr/bin/env python3
"""Prints the reference values of validation.yaml: plane Poiseuille flow u(y) = G y (H - y) / (2 mu)
at the walls and at the 16 cell-centre heights y = (j + 1/2) H / 16 of case.yaml (the points of
reference.points), and the flow rate Q = G H^3 W / (12 mu) (White, Viscous Fluid Flow, 3rd ed.,
eq. 3-42), with G = 3 Pa/m, mu = 0.5 Pa s, H = 1 m, channel depth W = 0.1 m (as in case.yaml)."""
G, mu, H, W, cells = 3.0, 0.5, 1.0, 0.1, 16


def u(y):
    return G * y * (H - y) / (2 * mu)


heights = [0.0] + [(j + 0.5) * H / cells for j in range(cells)] + [H]
points = [f"[{y:.12g}, {u(y):.12g}]" for y in heights]
print("points: [")
for i in range(0, len(points), 4):
    print("        " + ", ".join(points[i:i + 4]) + ("," if i + 4 < len(points) else "]"))
print(f"Q = {G * H**3 * W / (12 * mu):.12g} m^3/s")
