#!/usr/bin/env python3
"""Writes the particle positions of a grainflow particles_*.vtu as an OpenFOAM
kinematicCloudPositions file, shifted by (dx, dy, dz) (grainflow's bed spans x in [0, 0.015],
y in [0, 0.15]; the DPMFoam Goldschmidt tutorial's spans [-0.0075, 0.0075] x [-0.075, 0.075]),
or, when OUT ends in .csv, as grainflow csv_file insertion lines "x,y,z,r" (not shifted), so that
both codes can start from the same positions.
   vtu_positions_to_openfoam.py PARTICLES.vtu OUT [dx dy dz]
Reads grainflow's VTU layout: inline base64 binary arrays with a UInt64 byte-count header."""
import base64
import re
import struct
import sys


def array(text, path, name, components):
    match = re.search(rf'<DataArray type="Float64" Name="{name}" NumberOfComponents="{components}" '
                      r'format="binary">\s*([^<]*)<', text)
    if not match:
        sys.exit(f"{path}: no binary Float64 '{name}' array (a grainflow particles VTU is expected)")
    raw = base64.b64decode(match.group(1).strip())
    (size,) = struct.unpack_from("<Q", raw, 0)
    values = struct.unpack_from(f"<{size // 8}d", raw, 8)
    return [values[i:i + components] for i in range(0, len(values), components)]


def main():
    if len(sys.argv) not in (3, 6):
        sys.exit(__doc__)
    text = open(sys.argv[1], encoding="ascii").read()
    pts = array(text, sys.argv[1], "Points", 3)
    out_path = sys.argv[2]
    with open(out_path, "w", encoding="ascii") as out:
        if out_path.endswith(".csv"):
            radii = array(text, sys.argv[1], "radius", 1)
            if len(radii) != len(pts):
                sys.exit(f"{sys.argv[1]}: {len(pts)} points but {len(radii)} radii")
            for (x, y, z), (r,) in zip(pts, radii):
                out.write(f"{x:.17g},{y:.17g},{z:.17g},{r:.17g}\n")
        else:
            shift = [float(v) for v in sys.argv[3:6]] if len(sys.argv) == 6 else [-0.0075, -0.075, 0.0]
            out.write("FoamFile\n{\n    version 2.0;\n    format ascii;\n    class vectorField;\n"
                      "    object kinematicCloudPositions;\n}\n\n(\n")
            for x, y, z in pts:
                out.write(f"({x + shift[0]:.9g} {y + shift[1]:.9g} {z + shift[2]:.9g})\n")
            out.write(")\n")
    print(f"{len(pts)} positions written to {out_path}")


if __name__ == "__main__":
    main()
