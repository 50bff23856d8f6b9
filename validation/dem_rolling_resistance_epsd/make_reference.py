#!/usr/bin/env python3
"""Writes reference.csv: distance travelled by a sphere launched without spin on a floor, with sliding
friction mu and a rolling-resistance torque mu_r R F_n (constant directional torque, Ai et al. 2011
model A; EPSD model C reaches the same limiting torque mu_r R F_n once its spring is loaded).

Solid sphere, I = 2/5 m R^2, F_n = m g.
Sliding phase: dv/dt = -mu g, R dw/dt = 2.5 (mu - mu_r) g, until v = w R at
  t1 = v0 / (g (3.5 mu - 2.5 mu_r)), v1 = v0 - mu g t1, s1 = v0 t1 - mu g t1^2 / 2.
Rolling phase: a = -mu_r g / (1 + I / (m R^2)) = -mu_r g / 1.4 (Ai et al. 2011, Powder Technol. 206, 269,
sec. 3.1), s2 = 0.7 v1^2 / (mu_r g).  Distance s = s1 + s2.
"""
g, mu, v0 = 9.81, 0.5, 0.05
mu_rs = [0.02, 0.05, 0.1, 0.2]


def distance(mu_r):
    t1 = v0 / (g * (3.5 * mu - 2.5 * mu_r))
    v1 = v0 - mu * g * t1
    return v0 * t1 - 0.5 * mu * g * t1 * t1 + 0.7 * v1 * v1 / (mu_r * g)


with open("reference.csv", "w") as f:
    f.write("# Sphere launched at v0 = 0.05 m/s without spin on a floor, sliding friction mu = 0.5, rolling friction mu_r:\n")
    f.write("# slides until v = w R (t1 = v0 / (g (3.5 mu - 2.5 mu_r))), then rolls at a = -mu_r g / 1.4 (Ai, Chen, Rotter & Ooi 2011,\n")
    f.write("# Powder Technol. 206, 269) to rest; distance s = v0 t1 - mu g t1^2 / 2 + 0.7 v1^2 / (mu_r g); written by make_reference.py\n")
    f.write("mu_r [-],distance [m]\n")
    for m in mu_rs:
        f.write(f"{m:g},{distance(m):.12g}\n")
