#!/usr/bin/env python3
"""Reads a run's trajectory.xdmf back as a reader would (calibrate/output/trajectory_h5.hpp): every
frame a spatial collection of the grids "spheres" (Polyvertex) and "walls" (Triangle), every
DataItem a dataset of trajectory.h5 with the dimensions it declares, the triangles' indices inside
their vertices and their wall index inside wall_name, unit orientations, speeds that are the
velocities' magnitudes; and the walls named by --moving at other vertices in the last frame than
in the first frame that has them (a moving wall is drawn where it is), those named by --still at
the same. Prints one line per wall; exit 1 on a failure.

Usage: trajectory_xdmf_check.py RUN_DIR [--moving NAME ...] [--still NAME ...]
NAME is the wall's name as wall_name holds it without the shape ("upper_ring" for
"upper_ring (tube)")."""
import argparse
import os
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np


def fail(message):
    print("trajectory_xdmf_check: " + message, file=sys.stderr)
    sys.exit(1)


def dataset(h5, item):
    """The dataset a DataItem names, checked against its declared dimensions."""
    if item.get("Format") != "HDF":
        fail("DataItem not in HDF: " + ET.tostring(item, encoding="unicode"))
    name, _, path = item.text.strip().partition(":")
    if name != "trajectory.h5":
        fail("DataItem names another file: " + item.text)
    if path not in h5:
        fail("DataItem names a missing dataset: " + path)
    data = h5[path][()]
    dims = tuple(int(d) for d in item.get("Dimensions").split())
    if data.shape != dims:
        fail(f"{path}: shape {data.shape}, the XDMF declares {dims}")
    return path, data


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("run_dir")
    ap.add_argument("--moving", action="append", default=[])
    ap.add_argument("--still", action="append", default=[])
    a = ap.parse_args()
    root = ET.parse(os.path.join(a.run_dir, "trajectory.xdmf")).getroot()
    h5 = h5py.File(os.path.join(a.run_dir, "trajectory.h5"), "r")
    if h5.attrs["format"] != "seedcal trajectory 2":
        fail("format " + str(h5.attrs["format"]))
    temporal = root.find("Domain/Grid")
    if temporal.get("CollectionType") != "Temporal":
        fail("the outer grid is not a temporal collection")
    frames = temporal.findall("Grid")
    if len(frames) < 2:
        fail(f"{len(frames)} frames: need two to see a wall move")
    walls_per_frame = []  # per frame: {wall name: its vertices (k x 3)}
    times = []
    for frame in frames:
        if frame.get("CollectionType") != "Spatial":
            fail(frame.get("Name") + " is not a spatial collection")
        times.append(float(frame.find("Time").get("Value")))
        grids = {g.get("Name"): g for g in frame.findall("Grid")}
        if set(grids) != {"spheres", "walls"}:
            fail(f"{frame.get('Name')}: grids {sorted(grids)}")
        s = grids["spheres"]
        if s.find("Topology").get("TopologyType") != "Polyvertex":
            fail("spheres: not Polyvertex")
        n = int(s.find("Topology").get("NumberOfElements"))
        _, pos = dataset(h5, s.find("Geometry/DataItem"))
        arrays = {}
        for att in s.findall("Attribute"):
            path, data = dataset(h5, att.find("DataItem"))
            if data.shape[0] != n or att.get("Center") != "Node":
                fail(path + ": not one value per sphere")
            arrays[att.get("Name")] = data
        for key in ("radius_m", "body_id", "speed_m_s", "velocity_m_s", "orientation_wxyz"):
            if key not in arrays:
                fail("spheres: no attribute " + key)
        if not np.allclose(np.linalg.norm(arrays["velocity_m_s"], axis=1), arrays["speed_m_s"], rtol=1e-12, atol=0):
            fail("speed_m_s is not |velocity_m_s|")
        if not np.allclose(np.linalg.norm(arrays["orientation_wxyz"], axis=1), 1.0, atol=1e-9):
            fail("orientation_wxyz is not unit")
        if pos.shape != (n, 3):
            fail("position_m is not N x 3")
        w = grids["walls"]
        if w.find("Topology").get("TopologyType") != "Triangle":
            fail("walls: not Triangle")
        t = int(w.find("Topology").get("NumberOfElements"))
        group, tri = dataset(h5, w.find("Topology/DataItem"))
        group = group.rsplit("/", 1)[0]
        _, vert = dataset(h5, w.find("Geometry/DataItem"))
        att = w.find("Attribute")
        _, index = dataset(h5, att.find("DataItem"))
        if att.get("Name") != "wall_index" or att.get("Center") != "Cell" or tri.shape != (t, 3) or index.shape != (t,):
            fail("walls: wall_index is not one value per triangle")
        if tri.min() < 0 or tri.max() >= len(vert):
            fail("walls: a triangle's index outside the vertices")
        names = [x.decode() if isinstance(x, bytes) else x for x in h5[group + "/wall_name"][()]]
        if index.min() < 0 or index.max() >= len(names):
            fail("walls: a wall index outside wall_name")
        walls = {}
        for k, full in enumerate(names):
            used = np.unique(tri[index == k])
            if used.size == 0:
                fail(f"{group}: wall {full} has no triangle")
            walls[full.split(" (")[0]] = vert[used]
        walls_per_frame.append(walls)
    if times != sorted(times):
        fail("frame times not increasing")
    # Each wall from the first frame that has it (a lid comes in after the pour) to the last.
    first, since = {}, {}
    for t, walls in zip(times, walls_per_frame):
        for name, v in walls.items():
            first.setdefault(name, v)
            since.setdefault(name, t)
    last = walls_per_frame[-1]
    for name in first:
        if name not in last:
            fail(f"{name} is not in the last frame")
        moved = float(np.abs(last[name] - first[name]).max()) if last[name].shape == first[name].shape else float("inf")
        print(f"{name}: {len(first[name])} vertices, moved {moved:.6g} m from t = {since[name]:g} to {times[-1]:g} s")
    for name in a.moving:
        if name not in first:
            fail(f"no wall {name} (walls: {sorted(first)})")
        if not (np.abs(last[name] - first[name]).max() > 0.0):
            fail(f"{name} is drawn at the same vertices in its first and last frames")
    for name in a.still:
        if name not in first:
            fail(f"no wall {name} (walls: {sorted(first)})")
        if not np.array_equal(last[name], first[name]):
            fail(f"{name} does not move but its vertices changed")
    print(f"ok: {len(frames)} frames")


if __name__ == "__main__":
    main()
