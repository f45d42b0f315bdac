"""Paper Fig. 10: a density brush, f = max(0.25, min(1, d / r)) inside a geodesic disk.

    pvpython Examples/fig10_density_brush.py [--output output] [--check]
Shape Distributor's density brush (BrushCenter at the centre of a 10 x 10 square, BrushRadius
r, BrushDensity 0.25: d from the distributor's own geodesic engine) places the project's stars,
f times their size: small near the centre. Prints the count per unit area times f^2 in rings
around the centre (constant when the count follows 1 / f^2) and writes fig10_brush.png (the
square shaded by f, which on a plane is the formula of the Euclidean distance). --check: exit
with an error unless every ring is within 15% of their mean and the smallest shapes sit at the
centre.
"""
import argparse
import math
import os
import sys

import numpy
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from paraview.vtk.util.numpy_support import vtk_to_numpy

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--plugin", default=os.path.join(
    root, "build", "lib", "paraview-5.11", "plugins", "GeodesicShapes", "GeodesicShapes.so"))
parser.add_argument("--shape", default=os.path.join(root, "Data", "shapes", "star.png"))
parser.add_argument("--radius", type=float, default=4.0, help="brush radius r")
parser.add_argument("--output", default=os.path.join(root, "output"))
parser.add_argument("--check", action="store_true")
args = parser.parse_args()
LoadPlugin(args.plugin, remote=False, ns=globals())
os.makedirs(args.output, exist_ok=True)

n = 120
plane = Plane(Origin=[0, 0, 0], Point1=[10, 0, 0], Point2=[0, 10, 0], XResolution=n, YResolution=n)
square = Calculator(Input=Triangulate(Input=plane), AttributeType="Cell Data",
                    ResultArrayName="Direction", Function="iHat")
msdt = MSDTSource(ShapeFileNames=[args.shape])
shapes = ShapeDistributor(Input=square, Table=msdt, ShapeSize=0.3, Seed=1)
shapes.DirectionArray = ["CELLS", "Direction"]
shapes.BrushCenter = [5.0, 5.0, 0.0]
shapes.BrushRadius = args.radius
shapes.BrushDensity = 0.25
shapes.UpdatePipeline()
placed = servermanager.Fetch(shapes, idx=0)
pts = vtk_to_numpy(placed.GetPoints().GetData()).astype(float)
scale = vtk_to_numpy(placed.GetPointData().GetArray("Scale")).astype(float)
d = numpy.hypot(pts[:, 0] - 5.0, pts[:, 1] - 5.0)
rings = [(0.0, 1.0), (1.0, 2.0), (2.0, 3.0), (3.0, 4.0), (4.0, 4.8)]
values = []
for lo, hi in rings:
    inside = (d >= lo) & (d < hi)
    area = math.pi * (hi * hi - lo * lo)
    values.append((scale[inside] ** 2).sum() / area)  # count x f^2 per unit area
mean = sum(values) / len(values)
print("%d shapes; count x f^2 per unit area in rings around the brush centre: %s (mean %.3f)" % (
    len(scale), ", ".join("%.0f-%.0f: %.3f" % (r[0], r[1], v) for r, v in zip(rings, values)), mean))
smallest = pts[numpy.argmin(scale)]
print("smallest shape (f = %.2f) at distance %.2f from the centre" % (
    scale.min(), math.hypot(smallest[0] - 5, smallest[1] - 5)))

# The brush's factor, for the picture only (on the plane d is the Euclidean distance).
density = Calculator(Input=square, ResultArrayName="Density",
                     Function="max(0.25, min(1.0, sqrt((coordsX - 5)^2 + (coordsY - 5)^2) / %g))"
                     % args.radius)
view = CreateRenderView()
view.ViewSize = [700, 700]
view.OrientationAxesVisibility = 0
surface = Show(density, view)
ColorBy(surface, ("POINTS", "Density"))
surface.SetScalarBarVisibility(view, False)
GetColorTransferFunction("Density").ApplyPreset("Grayscale", True)
GetColorTransferFunction("Density").RescaleTransferFunction(0.0, 1.5)
outline = Show(OutputPort(shapes, 2), view)
outline.ColorArrayName = ["POINTS", ""]
outline.DiffuseColor = [0.6, 0.1, 0.1]
outline.AmbientColor = [0.6, 0.1, 0.1]
view.CameraPosition = [5, 5, 30]
view.CameraFocalPoint = [5, 5, 0]
view.CameraParallelProjection = 1
view.CameraParallelScale = 5.4
Render(view)
SaveScreenshot(os.path.join(args.output, "fig10_brush.png"), view)

if args.check:
    worst = max(abs(v / mean - 1.0) for v in values)
    if worst > 0.15 or math.hypot(smallest[0] - 5, smallest[1] - 5) > 1.0:
        sys.exit("fig10 check failed (largest ring deviation %.1f%%)" % (100 * worst))
    print("check passed (largest ring deviation %.1f%%)" % (100 * worst))
