"""The main job: four shape classes distributed on a surface, following a designed direction
field and a density brush, written as data files and a picture.

Run from the repository root (scripts/setup.sh demo does this under xvfb-run):
    pvpython Examples/main_job.py [--mesh Data/bumpy_sphere.ply] [--shapes a.png b.png ...]
        [--size 0.09] [--mode Random|Greedy|"Circumcircle Poisson disk"] [--seed 1]
        [--output output] [--check]
Pipeline: Cross Field (vector field with prescribed singularities at the poles and a stroke
along the equator) -> SVG Geodesic Distance from a brush point -> Calculator (density
f = clamp(d / 0.9, 0.45, 1): shapes shrink near the brush) -> Shape Distributor with MSDT Source
tables of the shapes (by default the four silhouettes of Data/shapes drawn by the project).
Writes, in the output folder: surface.vtp (mesh, Direction, Density), placements.vtp,
decals.vtp, outlines.vtp, main_job.png (the shapes textured on the surface) and main_job.pvsm
(the pipeline as a ParaView state).
--check: exit with an error unless the outputs exist and every class was placed.
"""
import argparse
import math
import os
import sys
import time

import numpy
from paraview.simple import *  # noqa: F401,F403
# Inline base64 (zlib) XML: ParaView 5.11 on Debian 12 cannot read back the raw appended
# data it writes by default (its libexpat rejects the binary bytes).
VTP = dict(DataMode="Binary", CompressorType="ZLib")
from paraview import servermanager
from paraview.vtk.util.numpy_support import numpy_to_vtk, vtk_to_numpy

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
shapes_dir = os.path.join(root, "Data", "shapes")
# (The first paragraph of the docstring, whole: its first line alone stops mid-sentence.)
parser = argparse.ArgumentParser(description=" ".join(__doc__.split("\n\n")[0].split()))
parser.add_argument("--plugin", default=os.path.join(
    root, "build", "lib", "paraview-5.11", "plugins", "GeodesicShapes", "GeodesicShapes.so"))
parser.add_argument("--mesh", default=os.path.join(root, "Data", "bumpy_sphere.ply"),
                    help="surface mesh in any format ParaView reads (PLY, OBJ, STL, VTP, ...)")
parser.add_argument("--shapes", nargs="+", metavar="IMAGE", help="shape silhouettes (PNG with "
                    "alpha, or dark on light), one class each (default: the four of Data/shapes)",
                    default=[
    os.path.join(shapes_dir, n) for n in ("star.png", "gull.png", "leaf.png", "fish.png")])
parser.add_argument("--size", type=float, default=None,
                    help="circumradius of the shapes at density 1 in world units (default: 0.09 "
                         "times the mesh's half extent)")
parser.add_argument("--mode", default="Greedy",
                    choices=["Random", "Greedy", "Circumcircle Poisson disk"])
parser.add_argument("--seed", type=int, default=1)
parser.add_argument("--output", default=os.path.join(root, "output"))
parser.add_argument("--check", action="store_true")
parser.add_argument("--quiet", action="store_true", help="no progress bars")
args = parser.parse_args()

for f in [args.plugin, args.mesh] + args.shapes:
    if not os.path.exists(f):
        sys.exit("main_job: cannot read %s" % f)
if args.size is not None and not (args.size > 0 and math.isfinite(args.size)):
    sys.exit("main_job: --size must be a positive number")
LoadPlugin(args.plugin, remote=False, ns=globals())
os.makedirs(args.output, exist_ok=True)
start = time.time()


def progress_bar(proxy, label):
    """A text progress bar on stderr for a long filter (its VTK object's ProgressEvent)."""
    if args.quiet:
        return
    algorithm = proxy.GetClientSideObject()
    state = {"last": -1}

    def report(caller, event):
        done = int(40 * caller.GetProgress())
        if done != state["last"]:
            state["last"] = done
            sys.stderr.write("\r%-22s [%s%s] %3d%%" % (label, "#" * done, " " * (40 - done),
                                                       int(100 * caller.GetProgress())))
            if done == 40:
                sys.stderr.write("\n")
            sys.stderr.flush()
    algorithm.AddObserver("ProgressEvent", report)

# Any surface format ParaView reads (PLY, OBJ, STL, VTP, VTK, VTU, ...), as triangles.
try:
    reader = OpenDataFile(args.mesh)
except RuntimeError:
    reader = None
if reader is None:
    sys.exit("main_job: cannot read %s: an unknown format or a corrupt file (ParaView reads PLY, "
             "OBJ, STL, VTP, VTK, VTU, ...)" % args.mesh)
mesh = Triangulate(Input=ExtractSurface(Input=reader))
mesh.UpdatePipeline()
if mesh.GetDataInformation().GetNumberOfCells() == 0:
    sys.exit("main_job: %s holds no surface (no polygons could be read)" % args.mesh)
bounds = mesh.GetDataInformation().GetBounds()
radius = 0.5 * max(bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4])
centre = [0.5 * (bounds[2 * k] + bounds[2 * k + 1]) for k in range(3)]
if args.size is None:
    args.size = 0.09 * radius

# 1. Direction field: a vector field (N = 1) turning about the poles (two +1 singularities,
# the Euler characteristic of a sphere is 2) and following a stroke drawn along the equator.
# On the user's own mesh: a point of the design that is not near the surface moves to the
# nearest mesh vertex, and a surface that is not a sphere (Euler characteristic V - E + F other
# than 2) gets the smoothest field following the stroke (singularities placed automatically).
surface_data = servermanager.Fetch(mesh)
vertices = vtk_to_numpy(surface_data.GetPoints().GetData()).astype(float)
triangles = vtk_to_numpy(surface_data.GetPolys().GetConnectivityArray()).reshape(-1, 3)
edges = numpy.sort(numpy.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]],
                                      triangles[:, [2, 0]]]), axis=1)
euler = (len(numpy.unique(triangles)) - len(numpy.unique(edges, axis=0)) + len(triangles))


def on_surface(point):
    d = ((vertices - numpy.array(point)) ** 2).sum(axis=1)
    nearest = int(numpy.argmin(d))
    return list(point) if math.sqrt(d[nearest]) <= 0.25 * radius else vertices[nearest].tolist()


top = on_surface([centre[0], centre[1], centre[2] + 1.2 * radius])
bottom = on_surface([centre[0], centre[1], centre[2] - 1.2 * radius])
poles = ProgrammableSource(OutputDataSetType="vtkPolyData")
poles.Script = """
import vtk
pts = vtk.vtkPoints()
pts.InsertNextPoint(%r, %r, %r)
pts.InsertNextPoint(%r, %r, %r)
idx = vtk.vtkDoubleArray()
idx.SetName("Index")
idx.InsertNextValue(1.0)
idx.InsertNextValue(1.0)
out = self.GetPolyDataOutput()
out.SetPoints(pts)
out.GetPointData().AddArray(idx)
""" % tuple(top + bottom)
stroke = PolyLineSource(Points=sum((on_surface([centre[0] + radius * math.cos(t),
                                                centre[1] + radius * math.sin(t),
                                                centre[2] + 0.25 * radius * math.sin(2 * t)])
                                    for t in [-0.6 + 0.1 * k for k in range(13)]), []))
if euler == 2:
    field = CrossField(Input=mesh, Singularities=poles, Strokes=stroke, Symmetry=1,
                       Mode="Prescribed singularities")
else:
    print("main_job: %s has Euler characteristic %d (not a sphere): smoothest field along the "
          "stroke" % (os.path.basename(args.mesh), euler))
    field = CrossField(Input=mesh, Strokes=stroke, Symmetry=1, Mode="Smoothest")
progress_bar(field, "Cross Field")

# 2. Density brush: geodesic distance from the mesh point nearest to the brush centre.
field.UpdatePipeline()
points = vtk_to_numpy(servermanager.Fetch(field).GetPoints().GetData())
brush = [centre[0], centre[1] - radius, centre[2]]
nearest = int(numpy.argmin(((points - numpy.array(brush)) ** 2).sum(axis=1)))
# (The discrete geodesic graph of accuracy 0.1: the graph the Shape Distributor's charts use by
# default, built once for both.)
distance = SVGGeodesicDistance(Input=field, SourceVertexIds=[nearest],
                               Solver="DGG (accuracy-bounded)", GraphAccuracy=0.1)
progress_bar(distance, "SVG Geodesic Distance")
density = Calculator(Input=distance, ResultArrayName="Density",
                     Function="max(0.45, min(1.0, GeodesicDistance / %g))" % (0.9 * radius))

# 3. Tables and distribution.
msdt = MSDTSource(ShapeFileNames=args.shapes, AngleBins=64, DistanceSteps=64, TextureSize=256)
shapes = ShapeDistributor(Input=density, Table=msdt, ShapeSize=args.size, Mode=args.mode,
                          Seed=args.seed)
shapes.DirectionArray = ["CELLS", "Direction"]
shapes.DensityArray = ["POINTS", "Density"]
shapes.ClassWeights = [1.0] * len(args.shapes)
progress_bar(msdt, "MSDT Source")
progress_bar(shapes, "Shape Distributor")
shapes.UpdatePipeline()
placed = servermanager.Fetch(shapes, idx=0)
classes = vtk_to_numpy(placed.GetPointData().GetArray("ClassId")) if placed.GetNumberOfPoints() else []
counts = [int((classes == k).sum()) for k in range(len(args.shapes))] if len(classes) else [0] * len(args.shapes)
if placed.GetNumberOfPoints() == 0:
    sys.exit("main_job: no shape placed (see the errors above)")
print("%d shapes (%s) on %s in %.1f s" % (placed.GetNumberOfPoints(), ", ".join(
    "%s %d" % (os.path.splitext(os.path.basename(s))[0], c) for s, c in zip(args.shapes, counts)),
    os.path.basename(args.mesh), time.time() - start))

# 4. Data files.
SaveData(os.path.join(args.output, "surface.vtp"), proxy=density, **VTP)
SaveData(os.path.join(args.output, "placements.vtp"), proxy=OutputPort(shapes, 0), **VTP)
SaveData(os.path.join(args.output, "decals.vtp"), proxy=OutputPort(shapes, 1), **VTP)
SaveData(os.path.join(args.output, "outlines.vtp"), proxy=OutputPort(shapes, 2), **VTP)

# 5. Picture: the surface coloured by density, each class's decals textured with its
# silhouette, transparent outside it (ParaView's own texture blending: the decals' texture
# coordinates stay in the texture square, so no repeat of it is drawn).
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOImage import vtkPNGWriter

silhouettes = servermanager.Fetch(msdt, idx=2)
channels = vtk_to_numpy(silhouettes.GetPointData().GetArray("Silhouette"))
if channels.ndim == 1:
    channels = channels[:, None]
colours = [(0.85, 0.55, 0.05), (0.15, 0.2, 0.55), (0.1, 0.5, 0.15), (0.7, 0.15, 0.15)]
view = CreateRenderView()
view.ViewSize = [900, 800]
view.OrientationAxesVisibility = 0
view.UseColorPaletteForBackground = 0
view.Background = [1.0, 1.0, 1.0]
surface = Show(density, view)
ColorBy(surface, ("POINTS", "Density"))
lut = GetColorTransferFunction("Density")
lut.ApplyPreset("Grayscale", True)
lut.RescaleTransferFunction(0.0, 1.6)
surface.SetScalarBarVisibility(view, False)
for k in range(len(args.shapes)):
    dims = silhouettes.GetDimensions()
    rgba = numpy.zeros((dims[0] * dims[1], 4), dtype=numpy.uint8)
    rgba[:, :3] = (255 * numpy.array(colours[k % len(colours)])).astype(numpy.uint8)
    rgba[:, 3] = channels[:, k]
    image = vtkImageData()
    image.SetDimensions(dims[0], dims[1], 1)
    array = numpy_to_vtk(rgba, deep=True)
    array.SetName("rgba")
    image.GetPointData().SetScalars(array)
    texture_file = os.path.join(args.output, "texture_%d.png" % k)
    writer = vtkPNGWriter()
    writer.SetFileName(texture_file)
    writer.SetInputData(image)
    writer.Write()
    one = Threshold(Input=OutputPort(shapes, 1), Scalars=["CELLS", "ClassId"],
                    LowerThreshold=k - 0.5, UpperThreshold=k + 0.5)
    decal = Show(one, view)
    decal.ColorArrayName = ["POINTS", ""]
    decal.Texture = CreateTexture(texture_file)
view.CameraPosition = [centre[0] + 2.2 * radius, centre[1] - 3.4 * radius, centre[2] + 1.6 * radius]
view.CameraFocalPoint = centre
view.CameraViewUp = [0, 0, 1]
view.ResetCamera()
Render(view)
# (Closer than ResetCamera's fit of the bounding sphere: the surface fills most of the picture.)
view.CameraPosition = [f + 0.8 * (p - f) for p, f in zip(view.CameraPosition, view.CameraFocalPoint)]
Render(view)
picture = os.path.join(args.output, "main_job.png")
SaveScreenshot(picture, view, ImageResolution=[900, 800])
# The pipeline as a ParaView state (File > Load State in the GUI; the data files it reads are
# the mesh and shape images given here).
SaveState(os.path.join(args.output, "main_job.pvsm"))
print("Results in %s: surface.vtp, placements.vtp, decals.vtp, outlines.vtp, main_job.png, "
      "main_job.pvsm" % args.output)

if args.check:
    problems = [f for f in ("surface.vtp", "placements.vtp", "decals.vtp", "outlines.vtp", "main_job.png",
                            "main_job.pvsm")
                if not os.path.getsize(os.path.join(args.output, f))]
    # The data files read back (numbers of points as written).
    written = {"surface.vtp": density, "placements.vtp": OutputPort(shapes, 0),
               "decals.vtp": OutputPort(shapes, 1), "outlines.vtp": OutputPort(shapes, 2)}
    for f, proxy in written.items():
        back = XMLPolyDataReader(FileName=[os.path.join(args.output, f)])
        back.UpdatePipeline()
        if (back.GetDataInformation().GetNumberOfPoints() !=
                proxy.GetDataInformation().GetNumberOfPoints()):
            problems.append(f + " (unreadable)")
    if problems or min(counts) == 0:
        sys.exit("main_job check failed: empty %s, counts %s" % (problems, counts))
    print("check passed")
