"""Paper Fig. 6: the single-class pipeline, step by step.

    pvpython Examples/fig06_single_class_steps.py [--mesh Data/torus.ply] [--shape star.png]
        [--output output] [--check]
1. the mesh; 2. a smooth cross field (Cross Field, N = 4, Symmetry written to field data);
3. the shape's minimum safe distance table (MSDT Source); 4. geodesic polar coordinates about
one point (the chart every shape is drawn in); 5. the distribution (Shape Distributor, Random)
with its decals. Prints one line per step and writes fig06_step<k>.png. --check: exit with an
error unless every step produced data (the field's index sum equal to the Euler
characteristic, a table with values between 0 and 2, shapes placed with decals).
"""
import argparse
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
parser.add_argument("--mesh", default=os.path.join(root, "Data", "torus.ply"))
parser.add_argument("--shape", default=os.path.join(root, "Data", "shapes", "star.png"))
parser.add_argument("--size", type=float, default=0.12)
parser.add_argument("--output", default=os.path.join(root, "output"))
parser.add_argument("--check", action="store_true")
args = parser.parse_args()
LoadPlugin(args.plugin, remote=False, ns=globals())
os.makedirs(args.output, exist_ok=True)
problems = []


def picture(k, *items):
    view = CreateRenderView()
    view.ViewSize = [500, 400]
    view.OrientationAxesVisibility = 0
    for proxy, colour in items:
        display = Show(proxy, view)
        if colour:
            ColorBy(display, colour)
    view.ResetCamera()
    Render(view)
    SaveScreenshot(os.path.join(args.output, "fig06_step%d.png" % k), view)


mesh = PLYReader(FileNames=[args.mesh])
mesh.UpdatePipeline()
info = mesh.GetDataInformation()
print("1. mesh: %d points, %d triangles" % (info.GetNumberOfPoints(), info.GetNumberOfCells()))
picture(1, (mesh, None))

field = CrossField(Input=mesh, Symmetry=4)
out = servermanager.Fetch(field)
chi = out.GetFieldData().GetArray("EulerCharacteristic").GetValue(0)
total = out.GetFieldData().GetArray("SingularityIndexSum").GetValue(0)
print("2. cross field: index sum %g, Euler characteristic %d" % (total, chi))
if abs(total - chi) > 1e-9:
    problems.append("index sum")
glyphs = Glyph(Input=CellCenters(Input=field), GlyphType="Line", OrientationArray=["POINTS", "Direction"],
               ScaleArray=["POINTS", "No scale array"], ScaleFactor=0.08)
picture(2, (field, ("POINTS", "SingularityIndex")), (glyphs, None))

msdt = MSDTSource(ShapeFileNames=[args.shape])
table = vtk_to_numpy(servermanager.Fetch(msdt).GetPointData().GetArray("SafeDistance"))
print("3. safe distance table: %d values in [%.3f, %.3f] (circumradius 1)" % (table.size, table.min(), table.max()))
if not (table.size > 0 and table.min() >= 0 and table.max() <= 2.0 + 1e-9):
    problems.append("table")
picture(3, (msdt, ("POINTS", "SafeDistance")))

polar = GeodesicPolarCoordinates(Input=field, SourceVertexId=0, Radius=4 * args.size)
polar.UpdatePipeline()
print("4. geodesic polar coordinates about point 0, radius %g" % (4 * args.size))
picture(4, (polar, ("POINTS", "PolarAngle")))

SetActiveSource(field)
shapes = ShapeDistributor(Input=field, Table=msdt, ShapeSize=args.size, Seed=2)
shapes.DirectionArray = ["CELLS", "Direction"]
shapes.DensityArray = ["POINTS", "None"]  # (ParaView may default it to the active scalars)
shapes.UpdatePipeline()
placed = servermanager.Fetch(shapes, idx=0)
decals = servermanager.Fetch(shapes, idx=1)
print("5. %d shapes, %d decal triangles" % (placed.GetNumberOfPoints(), decals.GetNumberOfCells()))
if placed.GetNumberOfPoints() == 0 or decals.GetNumberOfCells() == 0:
    problems.append("distribution")
picture(5, (mesh, None), (OutputPort(shapes, 2), ("CELLS", "ClassId")))

if args.check:
    if problems:
        sys.exit("fig06 check failed: %s" % problems)
    print("check passed")
