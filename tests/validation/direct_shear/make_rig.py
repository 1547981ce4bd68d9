#!/usr/bin/env python3
"""Writes the ZJ shear box of seedcal's direct_shear scene (geometry = "zj") as ASCII STL meshes for
LIGGGHTS: two thick rings (bore, outer surface, flat annular faces), the floor, and the loading cap,
a disc of the bore's diameter less 0.1 mm. Lengths in m, as in seedcal's DirectShearSpec.

Usage: make_rig.py OUT_DIR [--diameter 0.0618] [--height 0.020] [--wall 0.010] [--gap 0.001]
                           [--guide-factor 3.0] [--segments 180]
"""
import argparse
import math
import os


def facet(out, a, b, c):
    ux, uy, uz = (b[i] - a[i] for i in range(3))
    vx, vy, vz = (c[i] - a[i] for i in range(3))
    n = (uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx)
    m = math.sqrt(sum(x * x for x in n)) or 1.0
    out.append("facet normal %.9e %.9e %.9e\n outer loop\n" % tuple(x / m for x in n))
    for p in (a, b, c):
        out.append("  vertex %.9e %.9e %.9e\n" % p)
    out.append(" endloop\nendfacet\n")


def quad(out, a, b, c, d):
    facet(out, a, b, c)
    facet(out, a, c, d)


def ring(inner, outer, z0, z1, n):
    """A solid tube: bore, outer surface and the two annular faces (normals out of the solid)."""
    out = []
    for k in range(n):
        t0, t1 = 2 * math.pi * k / n, 2 * math.pi * (k + 1) / n
        c0, s0, c1, s1 = math.cos(t0), math.sin(t0), math.cos(t1), math.sin(t1)
        i0, i1 = (inner * c0, inner * s0), (inner * c1, inner * s1)
        o0, o1 = (outer * c0, outer * s0), (outer * c1, outer * s1)
        quad(out, (*i0, z0), (*i0, z1), (*i1, z1), (*i1, z0))          # bore, facing the axis
        quad(out, (*o0, z0), (*o1, z0), (*o1, z1), (*o0, z1))          # outer surface
        quad(out, (*i0, z1), (*o0, z1), (*o1, z1), (*i1, z1))          # top face
        quad(out, (*i0, z0), (*i1, z0), (*o1, z0), (*o0, z0))          # bottom face
    return out


def disc(radius, z, n, down):
    out = []
    for k in range(n):
        t0, t1 = 2 * math.pi * k / n, 2 * math.pi * (k + 1) / n
        a, b = (radius * math.cos(t0), radius * math.sin(t0), z), (radius * math.cos(t1), radius * math.sin(t1), z)
        facet(out, (0.0, 0.0, z), b, a) if down else facet(out, (0.0, 0.0, z), a, b)
    return out


def write(path, name, facets):
    with open(path, "w") as f:
        f.write("solid %s\n" % name)
        f.writelines(facets)
        f.write("endsolid %s\n" % name)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("out")
    p.add_argument("--diameter", type=float, default=0.0618)
    p.add_argument("--height", type=float, default=0.020)
    p.add_argument("--wall", type=float, default=0.010)
    p.add_argument("--gap", type=float, default=0.001)
    p.add_argument("--guide-factor", type=float, default=3.0)
    p.add_argument("--segments", type=int, default=180)
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    R, H, n = 0.5 * a.diameter, a.height, a.segments
    half = 0.5 * H
    # The polygon's flats lie inside the circle: place the vertices so the flats' mid-points sit on
    # the bore radius (the seeds meet the flats, as in seedcal they meet the circle).
    bore = R / math.cos(math.pi / n)
    write(os.path.join(a.out, "lower_ring.stl"), "lower_ring", ring(bore, R + a.wall, 0.0, half - 0.5 * a.gap, n))
    write(os.path.join(a.out, "upper_ring.stl"), "upper_ring",
          ring(bore, R + a.wall, half + 0.5 * a.gap, H + a.guide_factor * H, n))
    size = R + a.wall + 0.02
    floor = []
    quad(floor, (-size, -size, 0.0), (size, -size, 0.0), (size, size, 0.0), (-size, size, 0.0))
    write(os.path.join(a.out, "floor.stl"), "floor", floor)
    # The cap's lower face at z = 0 (moved into place by the deck); 0.1 mm radial clearance.
    write(os.path.join(a.out, "cap.stl"), "cap", disc(R - 0.0001, 0.0, n, down=True))


if __name__ == "__main__":
    main()
