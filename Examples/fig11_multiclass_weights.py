"""Paper Fig. 11: several classes with relative frequencies on the bumpy sphere.

    pvpython Examples/fig11_multiclass_weights.py [--output output] [--check]
The project's four shapes with ClassWeights 1 : 2 : 3 : 4 on Data/bumpy_sphere.ply (smooth
vector field), stopped at 300 shapes (MaximumShapes: before saturation the counts follow the
weights). Prints the counts per class and writes fig11_classes.png. --check: exit with an error
unless the counts increase with the weights and the heaviest class has 2.5x to 6x the lightest.
"""
import argparse
import os
import sys

import numpy
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from paraview.vtk.util.numpy_support import vtk_to_numpy

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
shapes_dir = os.path.join(root, "Data", "shapes")
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--plugin", default=os.path.join(
    root, "build", "lib", "paraview-5.11", "plugins", "GeodesicShapes", "GeodesicShapes.so"))
parser.add_argument("--mesh", default=os.path.join(root, "Data", "bumpy_sphere.ply"))
parser.add_argument("--output", default=os.path.join(root, "output"))
parser.add_argument("--check", action="store_true")
args = parser.parse_args()
LoadPlugin(args.plugin, remote=False, ns=globals())
os.makedirs(args.output, exist_ok=True)

mesh = PLYReader(FileNames=[args.mesh])
field = CrossField(Input=mesh, Symmetry=1)
names = ("star", "gull", "leaf", "fish")
msdt = MSDTSource(ShapeFileNames=[os.path.join(shapes_dir, n + ".png") for n in names])
shapes = ShapeDistributor(Input=field, Table=msdt, ShapeSize=0.07, Seed=4, MaximumShapes=300)
shapes.DirectionArray = ["CELLS", "Direction"]
shapes.DensityArray = ["POINTS", "None"]
shapes.ClassWeights = [1.0, 2.0, 3.0, 4.0]
shapes.UpdatePipeline()
classes = vtk_to_numpy(servermanager.Fetch(shapes, idx=0).GetPointData().GetArray("ClassId"))
counts = [int((classes == k).sum()) for k in range(4)]
print("weights 1:2:3:4 -> %s" % ", ".join("%s %d" % (n, c) for n, c in zip(names, counts)))

view = CreateRenderView()
view.ViewSize = [600, 600]
view.OrientationAxesVisibility = 0
Show(mesh, view)
lines = Show(OutputPort(shapes, 2), view)
lines.ColorArrayName = ["CELLS", "ClassId"]
Render(view)
SaveScreenshot(os.path.join(args.output, "fig11_classes.png"), view)
if args.check:
    ratio = counts[3] / max(1, counts[0])
    if not (counts[0] < counts[1] < counts[2] < counts[3] and 2.5 <= ratio <= 6.0):
        sys.exit("fig11 check failed")
    print("check passed (heaviest / lightest %.2f)" % ratio)
