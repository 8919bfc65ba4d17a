#!/usr/bin/env pvpython
"""Opens one run's views (written by `ambisim viz RUN_DIR`) in ParaView, coloured sensibly.

    pvpython scripts/paraview_run.py RUN_DIR [--colour planner|reference|error|pops] [--png FILE]
    paraview --script=scripts/paraview_run.py   (with AMBISIM_RUN_DIR=RUN_DIR in the environment)

What it shows, at the time slider's simulated seconds (the .pvd timesteps):
  terrain.vts        the surface in its albedo (sRGB, not mapped through a colour map);
  camera_path.vtp    the camera's path as an orange line;
  nodes.pvd          the planner's probes as points in their tone-mapped ambient colour;
  receivers.pvd      every receiver as a sphere glyph coloured by --colour:
                       planner    planner_view_rgb: what the planner showed toward the camera
                       reference  reference_view_rgb: what the truth would show
                       error      de2000_view, 0..10 CIEDE2000 (1 = just noticeable)
                       pops       viewed_pop, 1 where the receiver popped where seen
With --png the first timestep is rendered to FILE (offscreen, e.g. under xvfb-run) and the
script exits; otherwise, inside the ParaView GUI, the pipeline stays open.
"""
import argparse
import os
import sys

from paraview.simple import (  # type: ignore  # pylint: disable=import-error
    ColorBy, GetActiveViewOrCreate, GetAnimationScene, GetColorTransferFunction, Glyph,
    Hide, OpenDataFile, Render, ResetCamera, SaveScreenshot, Show)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run_dir", nargs="?", default=os.environ.get("AMBISIM_RUN_DIR"))
    parser.add_argument("--colour", choices=["planner", "reference", "error", "pops"],
                        default="planner")
    parser.add_argument("--png")
    args = parser.parse_args(argv)
    if not args.run_dir:
        parser.error("RUN_DIR (or AMBISIM_RUN_DIR) is required")
    views = os.path.join(args.run_dir, "views")
    for name in ("terrain.vts", "camera_path.vtp", "nodes.pvd", "receivers.pvd"):
        if not os.path.isfile(os.path.join(views, name)):
            sys.exit("paraview_run: %s: missing (run `ambisim viz %s` first)"
                     % (os.path.join(views, name), args.run_dir))

    view = GetActiveViewOrCreate("RenderView")
    view.Background = [1.0, 1.0, 1.0]

    terrain = OpenDataFile(os.path.join(views, "terrain.vts"))
    shown = Show(terrain, view)
    ColorBy(shown, ("POINTS", "albedo_rgb"))
    shown.MapScalars = 0  # the sRGB values are colours, not data

    path = OpenDataFile(os.path.join(views, "camera_path.vtp"))
    shown = Show(path, view)
    ColorBy(shown, None)
    shown.AmbientColor = shown.DiffuseColor = [1.0, 0.5, 0.0]
    shown.LineWidth = 3.0

    nodes = OpenDataFile(os.path.join(views, "nodes.pvd"))
    shown = Show(nodes, view)
    ColorBy(shown, ("POINTS", "ambient_rgb"))
    shown.MapScalars = 0
    shown.PointSize = 4.0

    receivers = OpenDataFile(os.path.join(views, "receivers.pvd"))
    spheres = Glyph(Input=receivers, GlyphType="Sphere")
    spheres.ScaleArray = ["POINTS", "No scale array"]
    spheres.ScaleFactor = 3.0
    spheres.GlyphMode = "All Points"
    Hide(receivers, view)
    shown = Show(spheres, view)
    array = {"planner": "planner_view_rgb", "reference": "reference_view_rgb",
             "error": "de2000_view", "pops": "viewed_pop"}[args.colour]
    ColorBy(shown, ("POINTS", array))
    if args.colour in ("planner", "reference"):
        shown.MapScalars = 0
    else:
        lut = GetColorTransferFunction(array)
        lut.ApplyPreset("Inferno (matplotlib)", True)
        lut.RescaleTransferFunction(0.0, 10.0 if args.colour == "error" else 1.0)
        shown.SetScalarBarVisibility(view, True)

    scene = GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()  # the slider runs in simulated seconds
    ResetCamera(view)
    Render(view)
    if args.png:
        SaveScreenshot(args.png, view, ImageResolution=[1200, 800])


if __name__ == "__main__":
    main(sys.argv[1:])
