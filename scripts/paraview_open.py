#!/usr/bin/env pvpython
"""Opens a run's trajectory in ParaView: the spheres as sphere glyphs of their own radius,
coloured by speed, and the walls as a translucent surface coloured by wall, over the run's frames.

Usage: pvpython scripts/paraview_open.py RUN_DIR [--screenshot PNG]

RUN_DIR holds trajectory.xdmf and trajectory.h5 (`seedcal run SCENE --out RUN_DIR --set
output.trajectory=true`; docs/scenes/README.md, "Trajectories"). With --screenshot the last frame
is saved as PNG and the script ends; without, an interactive window opens on the first frame
(in the ParaView GUI, open trajectory.xdmf with the Xdmf3ReaderS reader and apply the same
filters to play the frames).

Each frame of trajectory.xdmf is a collection of two blocks, "spheres" (points with radius_m,
body_id, speed_m_s, velocity_m_s, orientation_wxyz) and "walls" (triangles with wall_index). A
sphere is drawn by the Glyph filter's Sphere source (radius 0.5) scaled by radius_m times 2, so
its radius is radius_m. Written for ParaView 5.6 and later (ExtractBlock's selectors from 5.10,
block indices before).
"""
import argparse
import os
import sys

from paraview.simple import (ColorBy, ExtractBlock, GetActiveViewOrCreate, GetAnimationScene, Glyph, Interact,
                             Render, SaveScreenshot, Show, Xdmf3ReaderS)


def block(source, name, index):
    """The block `name` of every frame (`index`: its place in the frame's collection, for
    ParaView before 5.10: 0 is the collection, 1 the spheres, 2 the walls)."""
    extract = ExtractBlock(Input=source)
    if "Selectors" in extract.ListProperties():
        extract.Selectors = ["//" + name]
    else:
        extract.BlockIndices = [index]
    return extract


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run_dir", help="a run's --out folder")
    ap.add_argument("--screenshot", metavar="PNG", help="save the last frame as PNG and exit")
    a = ap.parse_args(argv)
    xdmf = os.path.join(a.run_dir, "trajectory.xdmf")
    if not os.path.isfile(xdmf):
        sys.exit("paraview_open.py: no " + xdmf + " (run the scene with --set output.trajectory=true)")

    reader = Xdmf3ReaderS(FileName=[xdmf])
    view = GetActiveViewOrCreate("RenderView")

    glyph = Glyph(Input=block(reader, "spheres", 1), GlyphType="Sphere")
    glyph.ScaleArray = ["POINTS", "radius_m"]
    glyph.ScaleFactor = 2.0  # the source's radius 0.5 times 2 radius_m: radius_m
    glyph.GlyphMode = "All Points"
    glyph.OrientationArray = ["POINTS", "No orientation array"]  # a sphere looks the same turned
    glyph.GlyphType.ThetaResolution = 16
    glyph.GlyphType.PhiResolution = 12
    spheres = Show(glyph, view)
    ColorBy(spheres, ("POINTS", "speed_m_s"))
    spheres.RescaleTransferFunctionToDataRange(True, False)
    spheres.SetScalarBarVisibility(view, True)

    walls = Show(block(reader, "walls", 2), view)
    ColorBy(walls, ("CELLS", "wall_index"))
    walls.Opacity = 0.3

    # z is up in seedcal (gravity along -z): look from -y, a little above, at the whole rig.
    view.CameraPosition = [0.0, -3.0, 1.2]
    view.CameraFocalPoint = [0.0, 0.0, 0.0]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.ResetCamera()

    scene = GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    times = reader.TimestepValues
    times = list(times) if isinstance(times, (list, tuple)) else [times]
    if a.screenshot:
        scene.AnimationTime = times[-1]
        view.ResetCamera()
        Render(view)
        SaveScreenshot(a.screenshot, view, ImageResolution=[1280, 800])
        print("paraview_open.py: " + a.screenshot + " (t = %g s, %d frames)" % (times[-1], len(times)))
        return
    Render(view)
    Interact(view)


if __name__ == "__main__":
    main(sys.argv[1:])
