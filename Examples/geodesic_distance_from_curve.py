"""Geodesic distance from a curve: a closed polyline around the bundled torus as the source.

Run from the repository root:
    xvfb-run -a pvpython Examples/geodesic_distance_from_curve.py [--output output]
The curve is a tilted circle drawn in space around the torus; SVG Geodesic Distance samples it,
snaps the samples onto the surface and computes the distance to the whole curve (not only to
its points). Writes <output>/geodesic_distance_from_curve.{vtp,png}.
"""
import argparse
import math
import os
import sys

from paraview.simple import *  # noqa: F401,F403
# Inline base64 (zlib) XML: ParaView 5.11 on Debian 12 cannot read back the raw appended
# data it writes by default (its libexpat rejects the binary bytes).
VTP = dict(DataMode="Binary", CompressorType="ZLib")

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--plugin", default=os.path.join(
    root, "build", "lib", "paraview-5.11", "plugins", "GeodesicShapes", "GeodesicShapes.so"))
parser.add_argument("--mesh", default=os.path.join(root, "Data", "torus.ply"))
parser.add_argument("--solver", default="SVG (label-correcting)",
                    choices=["SVG (label-correcting)", "SVG (Dijkstra)", "Exact"])
parser.add_argument("--output", default=os.path.join(root, "output"))
args = parser.parse_args()

LoadPlugin(args.plugin, remote=False, ns=globals())
os.makedirs(args.output, exist_ok=True)

mesh = PLYReader(FileNames=[args.mesh])
# A circle of radius 1.4 around the z axis (the torus's outer equator, Data/torus.ply has radii
# 1 and 0.4), tilted by 12 degrees: it is snapped onto the outer side of the tube, above the
# equator on one side and below it on the other. 96 points, closed.
points = []
tilt = math.radians(12.0)
for i in range(96):
    a = 2.0 * math.pi * i / 96
    x, y = 1.4 * math.cos(a), 1.4 * math.sin(a)
    points += [x, y * math.cos(tilt), y * math.sin(tilt)]
curve = PolyLineSource(Points=points, Closed=1)

geodesic = SVGGeodesicDistance(Input=mesh, Sources=curve, Solver=args.solver)
geodesic.UpdatePipeline()
low, high = geodesic.PointData["GeodesicDistance"].GetRange()
print("%s: %s distance from a closed curve in [%g, %g]" % (
    os.path.basename(args.mesh), args.solver, low, high))
SaveData(os.path.join(args.output, "geodesic_distance_from_curve.vtp"), proxy=geodesic, **VTP)

view = CreateRenderView()
view.ViewSize = [1000, 700]
view.OrientationAxesVisibility = 0
surface = Show(geodesic, view)
ColorBy(surface, ("POINTS", "GeodesicDistance"))
GetColorTransferFunction("GeodesicDistance").ApplyPreset("Viridis (matplotlib)", True)
isolines = Contour(Input=geodesic, ContourBy=["POINTS", "GeodesicDistance"],
                   Isosurfaces=[high * (i + 0.5) / 12 for i in range(12)], ComputeScalars=False)
lines = Show(isolines, view)
lines.ColorArrayName = ["POINTS", ""]
lines.AmbientColor = lines.DiffuseColor = [0.05, 0.05, 0.05]
lines.LineWidth = 2.0
# The curve as given, in space (the filter snaps its samples onto the surface).
source_line = Show(curve, view)
source_line.AmbientColor = source_line.DiffuseColor = [1.0, 0.2, 0.2]
source_line.LineWidth = 4.0
Render(view)
view.ResetCamera()
camera = view.GetActiveCamera()
camera.Elevation(-50)
view.ResetCamera()
Render(view)
png = os.path.join(args.output, "geodesic_distance_from_curve.png")
SaveScreenshot(png, view, ImageResolution=[1000, 700])
print("wrote", png)

Delete(view)
del view
sys.exit(0)
