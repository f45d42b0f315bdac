"""Paper Fig. 14: eagles packed by their exact silhouettes against their bounding ellipses.

    pvpython Examples/fig14_eagles_vs_ellipses.py [--eagle file.png] [--output output] [--check]
The baseline treats every eagle as its bounding ellipse (the smallest-area ellipse containing
the silhouette): its tables come from MSDT Source fed with that
ellipse as a polygon, and the eagle is drawn in it. The same 10 x 10 square, field-aligned,
Random mode, 3 seeds each. Prints both counts; writes fig14_eagles.png. --check: exit with an
error unless the exact silhouettes fit at least 1.15x as many eagles as the ellipses.
The eagle is openclipart's eagle_01 (Debian openclipart-png) when installed, else the project's
gull (Data/shapes/gull.png).
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
default_eagle = "/usr/share/openclipart/png/animals/birds/eagle_01.png"
if not os.path.exists(default_eagle):
    default_eagle = os.path.join(root, "Data", "shapes", "gull.png")
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--plugin", default=os.path.join(
    root, "build", "lib", "paraview-5.11", "plugins", "GeodesicShapes", "GeodesicShapes.so"))
parser.add_argument("--eagle", default=default_eagle)
parser.add_argument("--seeds", type=int, default=3)
parser.add_argument("--output", default=os.path.join(root, "output"))
parser.add_argument("--check", action="store_true")
args = parser.parse_args()
LoadPlugin(args.plugin, remote=False, ns=globals())
os.makedirs(args.output, exist_ok=True)

# The silhouette as MSDT Source sees it (its Silhouettes output: the square around the circle).
eagle = MSDTSource(ShapeFileNames=[args.eagle], TextureSize=512, MaximumAspectRatio=1000)
eagle.UpdatePipeline()
image = servermanager.Fetch(eagle, idx=2)
n = image.GetDimensions()[0]
mask = vtk_to_numpy(image.GetPointData().GetArray("Silhouette")).reshape(n, n) > 127
ys, xs = numpy.nonzero(mask)
pts = numpy.column_stack([(2 * xs + 1) / n - 1.0, (2 * ys + 1) / n - 1.0])  # class units / radius
# Bounding ellipse: the smallest-area ellipse holding every pixel centre (Khachiyan's
# algorithm on the pixels' convex hull corners, grown by half a pixel).
def convex_hull(points):
    """Monotone chain: the hull's corners."""
    p = sorted(set(map(tuple, points)))
    def half(seq):
        out = []
        for q in seq:
            while len(out) >= 2 and ((out[-1][0] - out[-2][0]) * (q[1] - out[-2][1]) -
                                     (out[-1][1] - out[-2][1]) * (q[0] - out[-2][0])) <= 0:
                out.pop()
            out.append(q)
        return out
    return numpy.array(half(p)[:-1] + half(p[::-1])[:-1])


hull = convex_hull(pts)
q = numpy.column_stack([hull, numpy.ones(len(hull))]).T
u = numpy.full(len(hull), 1.0 / len(hull))
for _ in range(2000):
    x = q @ numpy.diag(u) @ q.T
    m = numpy.einsum("ij,ji->i", q.T @ numpy.linalg.inv(x), q)
    j = int(numpy.argmax(m))
    step = (m[j] - 3.0) / (3.0 * (m[j] - 1.0))
    if step < 1e-7:
        break
    u = (1 - step) * u
    u[j] += step
mean = hull.T @ u
shape = numpy.linalg.inv(hull.T @ numpy.diag(u) @ hull - numpy.outer(mean, mean)) / 2.0
values, vectors = numpy.linalg.eigh(shape)
a, b = 1.0 / numpy.sqrt(values) + 1.0 / n
ring = [mean + vectors @ numpy.array([a * math.cos(t), b * math.sin(t)])
        for t in numpy.linspace(0, 2 * math.pi, 96, endpoint=False)]
ellipse = ProgrammableSource(OutputDataSetType="vtkPolyData")
ellipse.Script = """
import vtk
pts = vtk.vtkPoints()
ids = vtk.vtkIdList()
for p in %r:
    ids.InsertNextId(pts.InsertNextPoint(p[0], p[1], 0.0))
polys = vtk.vtkCellArray()
polys.InsertNextCell(ids)
out = self.GetPolyDataOutput()
out.SetPoints(pts)
out.SetPolys(polys)
""" % [tuple(map(float, p)) for p in ring]
ellipse_tables = MSDTFromPolygons(Input=ellipse, MaximumAspectRatio=1000)
eagle_tables = MSDTSource(ShapeFileNames=[args.eagle], MaximumAspectRatio=1000)

plane = Plane(Origin=[0, 0, 0], Point1=[10, 0, 0], Point2=[0, 10, 0], XResolution=100, YResolution=100)
square = Calculator(Input=Triangulate(Input=plane), AttributeType="Cell Data",
                    ResultArrayName="Direction", Function="iHat")
counts = {}
# Both in units of the eagle's circumradius (0.5 in the square): the ellipse's circumradius is
# its major semi-axis.
for name, tables, size in (("ellipses", ellipse_tables, 0.5 * float(numpy.maximum(a, b))), ("eagles", eagle_tables, 0.5)):
    SetActiveSource(square)  # (array defaults are taken from the active source at creation)
    shapes = ShapeDistributor(Input=square, Table=tables, ShapeSize=size)
    shapes.DirectionArray = ["CELLS", "Direction"]
    shapes.DensityArray = ["POINTS", "None"]
    total = 0
    for seed in range(args.seeds):
        shapes.Seed = seed
        shapes.UpdatePipeline()
        total += servermanager.Fetch(shapes, idx=0).GetNumberOfPoints()
    counts[name] = total / float(args.seeds)
    if name == "eagles":
        view = CreateRenderView()
        view.ViewSize = [700, 700]
        view.OrientationAxesVisibility = 0
        Show(plane, view)
        lines = Show(OutputPort(shapes, 2), view)
        lines.ColorArrayName = ["POINTS", ""]
        lines.DiffuseColor = [0.3, 0.15, 0.05]
        lines.AmbientColor = [0.3, 0.15, 0.05]
        view.CameraPosition = [5, 5, 30]
        view.CameraFocalPoint = [5, 5, 0]
        view.CameraParallelProjection = 1
        view.CameraParallelScale = 5.4
        Render(view)
        SaveScreenshot(os.path.join(args.output, "fig14_eagles.png"), view)
ratio = counts["eagles"] / counts["ellipses"]
print("%s: bounding ellipses (axes %.2f x %.2f of the circumradius) %.1f, exact silhouettes %.1f: %.2fx"
      % (os.path.basename(args.eagle), a, b, counts["ellipses"], counts["eagles"], ratio))
if args.check:
    if not ratio >= 1.15:
        sys.exit("fig14 check failed")
    print("check passed")
