"""Paper Fig. 13: the same surface at two resolutions gets the same number of shapes.

    pvpython Examples/fig13_two_resolutions.py [--seeds 3] [--output output] [--check]
Data/bumpy_sphere.ply and its linear subdivision (Subdivide: every triangle split into four,
the surface unchanged), a smooth vector field (Cross Field, N = 1) on each, the project's four
shapes. Prints the mean counts; writes fig13_coarse.png and fig13_fine.png. --check: exit with
an error unless the counts are within 5% of each other.
"""
import argparse
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
shapes_dir = os.path.join(root, "Data", "shapes")
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--plugin", default=os.path.join(
    root, "build", "lib", "paraview-5.11", "plugins", "GeodesicShapes", "GeodesicShapes.so"))
parser.add_argument("--mesh", default=os.path.join(root, "Data", "bumpy_sphere.ply"))
parser.add_argument("--seeds", type=int, default=3)
parser.add_argument("--size", type=float, default=0.1)
parser.add_argument("--output", default=os.path.join(root, "output"))
parser.add_argument("--check", action="store_true")
args = parser.parse_args()
LoadPlugin(args.plugin, remote=False, ns=globals())
os.makedirs(args.output, exist_ok=True)

coarse = PLYReader(FileNames=[args.mesh])
fine = Subdivide(Input=coarse, NumberofSubdivisions=1)
msdt = MSDTSource(ShapeFileNames=[os.path.join(shapes_dir, n)
                                  for n in ("star.png", "gull.png", "leaf.png", "fish.png")])
counts = {}
for name, mesh in (("coarse", coarse), ("fine", fine)):
    field = CrossField(Input=mesh, Symmetry=1)
    shapes = ShapeDistributor(Input=field, Table=msdt, ShapeSize=args.size)
    shapes.DirectionArray = ["CELLS", "Direction"]
    shapes.DensityArray = ["POINTS", "None"]
    total = 0
    for seed in range(args.seeds):
        shapes.Seed = seed
        shapes.UpdatePipeline()
        total += servermanager.Fetch(shapes, idx=0).GetNumberOfPoints()
    counts[name] = total / float(args.seeds)
    faces = mesh.GetDataInformation().GetNumberOfCells()
    print("%s: %d triangles, %.1f shapes (mean of %d seeds)" % (name, faces, counts[name], args.seeds))
    view = CreateRenderView()
    view.ViewSize = [500, 500]
    view.OrientationAxesVisibility = 0
    Show(mesh, view)
    lines = Show(OutputPort(shapes, 2), view)
    lines.ColorArrayName = ["CELLS", "ClassId"]
    Render(view)
    SaveScreenshot(os.path.join(args.output, "fig13_%s.png" % name), view)
gap = abs(counts["fine"] - counts["coarse"]) / counts["fine"]
print("counts %.1f%% apart" % (100 * gap))
if args.check:
    if not gap <= 0.05:
        sys.exit("fig13 check failed")
    print("check passed")
