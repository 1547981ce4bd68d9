#!/usr/bin/env python3
"""Writes the conical bottom of a hopper as an ASCII STL (millimetres): the frustum between the
orifice circle (diameter ORIFICE_MM at z = 0) and the rim circle (diameter TOP_MM), its wall at
ANGLE_DEG above the horizontal, as SEGMENTS flat facets around. data/scenes/examples/hopper.toml
reads the file this writes with its defaults:

    python3 scripts/hopper_stl.py > data/scenes/examples/hopper_cone.stl
"""
import argparse
import math
import sys


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--orifice-mm", type=float, default=60.0)
    ap.add_argument("--top-mm", type=float, default=150.0)
    ap.add_argument("--angle-deg", type=float, default=30.0)
    ap.add_argument("--segments", type=int, default=48)
    a = ap.parse_args()
    r0, r1 = 0.5 * a.orifice_mm, 0.5 * a.top_mm
    h = (r1 - r0) * math.tan(math.radians(a.angle_deg))
    ring = lambda r, z, k: (r * math.cos(2 * math.pi * k / a.segments), r * math.sin(2 * math.pi * k / a.segments), z)
    out = sys.stdout
    out.write("solid hopper_cone\n")
    for k in range(a.segments):
        p0, p1 = ring(r0, 0.0, k), ring(r0, 0.0, k + 1)
        q0, q1 = ring(r1, h, k), ring(r1, h, k + 1)
        for tri in ((p0, p1, q1), (p0, q1, q0)):
            u = [tri[1][i] - tri[0][i] for i in range(3)]
            v = [tri[2][i] - tri[0][i] for i in range(3)]
            n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
            ln = math.sqrt(sum(c * c for c in n))
            out.write("  facet normal %.6e %.6e %.6e\n    outer loop\n" % tuple(c / ln for c in n))
            for p in tri:
                out.write("      vertex %.6f %.6f %.6f\n" % p)
            out.write("    endloop\n  endfacet\n")
    out.write("endsolid hopper_cone\n")


if __name__ == "__main__":
    main()
