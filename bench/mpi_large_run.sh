#!/usr/bin/env bash
# A run of about 2 million spheres on 2 MPI ranks, 100 steps: that it completes on this machine,
# its cost per particle-step, and the peak memory of each rank (per owned particle).
# The bed: a 126^3 lattice of spheres d = 2 mm, 0.2 mm apart, periodic in x and y, on a floor,
# split [2, 1, 1]; one thread per rank. The peak includes the start, when every rank creates
# the whole lattice before it keeps its box's particles, and on rank 0 the end-of-run checkpoint
# it gathers.
# COUPLED=1: the same bed as a CFD-DEM case, 100 coupling steps (one DEM step each): air blown up
# through it from an inlet at the bottom to a pressure outlet at the top (Gidaspow drag, divided
# void fraction) on a grid of cells 4 lattice spacings wide (8.8 mm, 4.4 diameters).
#   usage: [COUPLED=1] bash bench/mpi_large_run.sh [GRAINFLOW] [LATTICE_SIDE]   (defaults: build/grainflow, 126)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
grainflow=${1:-$here/build/grainflow}
side=${2:-126}
work=$(mktemp -d /tmp/grainflow_large_run.XXXXXX)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
length=$(python3 -c "print($side * 0.0022)")
cat >"$work/case.yaml" <<CASE
case: {name: large_run}
domain: {min: [0, 0, 0], max: [$length, $length, $(python3 -c "print($side * 0.0022 + 0.02)")], periodic: [1, 1, 0], decomposition: [2, 1, 1]}
time: {end: 0.001, dem_step: 1.0e-5}
materials:
  - {name: glass, density: 2500.0, youngs_modulus: 1.0e7, poisson_ratio: 0.3}
contact: {law: hertz_mindlin, restitution: 0.5, friction: 0.5}
walls:
  - {type: plane, name: floor, point: [0, 0, 0], normal: [0, 0, 1], material: glass}
insertion:
  - {type: lattice, material: glass, origin: [0.0011, 0.0011, 0.0011], spacing: 0.0022, nx: $side, ny: $side, nz: $side, diameter: 0.002}
CASE
if [ "${COUPLED:-0}" = 1 ]; then
  # cells 4 lattice spacings wide; 3 cells of freeboard above the lattice
  cells_xy=$(( (side + 3) / 4 ))
  python3 - "$work/case.yaml" "$cells_xy" "$(( cells_xy + 3 ))" <<'PY'
import sys, yaml
path, nxy, nz = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
c = yaml.safe_load(open(path))
c["case"]["name"] = "large_coupled_run"
h = 0.0022 * 4
c["domain"]["max"] = [nxy * h, nxy * h, nz * h]
c["fluid"] = {"density": 1.2, "viscosity": 1.8e-5, "cells": [nxy, nxy, nz],
              "boundaries": {"z_min": {"type": "inlet", "velocity": [0.0, 0.0, 0.5]},
                             "z_max": {"type": "pressure_outlet"}}}
c["coupling"] = {"drag_law": "gidaspow", "void_fraction": "divided"}
c["time"]["coupling_interval"] = 1
yaml.safe_dump(c, open(path, "w"), sort_keys=False)
PY
fi
mpirun --oversubscribe -np 2 /usr/bin/time -f "rank peak memory %M kB" "$grainflow" run "$work/case.yaml" \
  --threads 1 --output "$work/out" >"$work/log" 2>&1 || { cat "$work/log"; exit 1; }
python3 - "$work/log" "$side" <<'PY'
import re, sys
text, side = open(sys.argv[1]).read(), int(sys.argv[2])
particles = side ** 3
peaks = [int(k) for k in re.findall(r"rank peak memory (\d+) kB", text)]
ns = re.search(r"([0-9.e+]+) ns per particle-step", text).group(1)
steps = re.search(r"(\d+) builds in (\d+) DEM steps", text).group(2)
coupled = "large_coupled_run" in text
print(f"{particles} particles on 2 ranks, {steps} {'coupling' if coupled else 'DEM'} steps completed; "
      f"{float(ns):.1f} ns per particle-step (all phases)")
for rank, kb in enumerate(sorted(peaks)):
    print(f"  a rank's peak memory: {kb / 1024:.0f} MiB, {kb * 1024 / (particles / 2):.0f} bytes per owned particle")
print(re.search(r"^MPI.*$", text, re.M).group(0))
PY
