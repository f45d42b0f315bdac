"""pvpython test: the whole pipeline as a user runs it, MSDT Source + Cross Field + Shape Distributor.

- Two shapes written by the test (a star and a 4:1 bar, which MSDT Source splits into parts) on
  the bundled planar grid, a cross field, a density ramp built with a Calculator.
- Placements: both classes present, Scale equal to the density at each centre, unit tangent
  directions, cell ids of the input; the outlines (drawn on the surface by the filter) of any two
  shapes neither cross nor contain each other (an overlap test independent of the tables).
- Decals: texture coordinates in the class square; ShapeId/ClassId cell arrays.
- Same Placements with 1 and 2 threads; Circumcircle Poisson disk places fewer shapes than
  Random; MaximumShapes; bad parameters give empty outputs. Render to a PNG.

Usage: pvpython TestShapeDistributor.py --plugin <GeodesicShapes.so> --data <Data dir> --temp <dir>
"""
import math
import os
import tempfile

import numpy
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from paraview.vtk.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOImage import vtkPNGWriter

import gs_test
from gs_test import check

args = gs_test.arguments(plugin=gs_test.REQUIRED, data=gs_test.REQUIRED, temp=None)


def write_png(path, inside):
    height, width = inside.shape
    pixels = numpy.zeros((height, width, 4), dtype=numpy.uint8)
    pixels[..., 3] = numpy.where(inside[::-1], 255, 0)  # first row at the bottom in VTK
    image = vtkImageData()
    image.SetDimensions(width, height, 1)
    array = numpy_to_vtk(pixels.reshape(width * height, -1), deep=True)
    array.SetName("pixels")
    image.GetPointData().SetScalars(array)
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputData(image)
    writer.Write()


def inside_polygon(px, py, poly):
    """Even-odd point in polygon, vectorized over points."""
    inside = numpy.zeros(px.shape, dtype=bool)
    n = len(poly)
    for k in range(n):
        (x0, y0), (x1, y1) = poly[k], poly[(k + 1) % n]
        crosses = (y0 > py) != (y1 > py)
        with numpy.errstate(divide="ignore", invalid="ignore"):
            xc = x0 + (py - y0) * (x1 - x0) / (y1 - y0)
        inside ^= crosses & (px < xc)
    return inside


LoadPlugin(args.plugin, remote=False, ns=globals())
check("ShapeDistributor" in globals(), "the plugin does not define ShapeDistributor")

temp = tempfile.mkdtemp(prefix="TestShapeDistributor_", dir=args.temp)
size = 96
y, x = numpy.mgrid[0:size, 0:size] + 0.5
star = [(48 + (44 if k % 2 == 0 else 18) * math.cos(math.pi / 2 + math.pi * k / 5),
         48 + (44 if k % 2 == 0 else 18) * math.sin(math.pi / 2 + math.pi * k / 5)) for k in range(10)]
star_file = os.path.join(temp, "star.png")
bar_file = os.path.join(temp, "bar.png")
write_png(star_file, inside_polygon(x, y, star))
write_png(bar_file, (numpy.abs(x - 48) < 40) & (numpy.abs(y - 48) < 10))

msdt = MSDTSource(ShapeFileNames=[star_file, bar_file], AngleBins=48, DistanceSteps=48)
mesh = PLYReader(FileNames=[os.path.join(args.data, "planar_grid.ply")])
field = CrossField(Input=mesh, Symmetry=4)
density = Calculator(Input=field, ResultArrayName="Density", Function="0.6+0.4*coordsX")


def fetch(proxy, port):
    return servermanager.Fetch(proxy, idx=port)


# Defaults as a user gets them on an up-to-date input: no density, the field's Direction.
density.UpdatePipeline()
SetActiveSource(density)
fresh = ShapeDistributor(Input=density, Table=msdt)
check(fresh.DensityArray[1] == "None", "DensityArray should default to None, got %s" % fresh.DensityArray)
check(fresh.DirectionArray[1] == "Direction",
      "DirectionArray should default to Direction, got %s" % fresh.DirectionArray)
Delete(fresh)

shapes = ShapeDistributor(Input=density, Table=msdt, ShapeSize=0.07, Seed=3)
shapes.DirectionArray = ["CELLS", "Direction"]
shapes.DensityArray = ["POINTS", "Density"]
shapes.ClassWeights = [1.0, 1.0]
shapes.MaximalFailures = 5000
shapes.UpdatePipeline()
placed = fetch(shapes, 0)
n = placed.GetNumberOfPoints()
print("placed", n, "shapes; candidates",
      placed.GetFieldData().GetArray("NumberOfCandidates").GetValue(0))
check(n > 30, "too few shapes placed: %d" % n)
if n > 0:
    pts = vtk_to_numpy(placed.GetPoints().GetData()).astype(float)
    cls = vtk_to_numpy(placed.GetPointData().GetArray("ClassId"))
    scale = vtk_to_numpy(placed.GetPointData().GetArray("Scale")).astype(float)
    direction = vtk_to_numpy(placed.GetPointData().GetArray("Direction")).astype(float)
    faces = vtk_to_numpy(placed.GetPointData().GetArray("FaceId"))
    check(set(cls.tolist()) == {0, 1}, "both classes expected, got %s" % set(cls.tolist()))
    check(numpy.allclose(scale, 0.6 + 0.4 * pts[:, 0], atol=1e-9), "Scale is not the density")
    check(numpy.allclose(numpy.linalg.norm(direction, axis=1), 1.0, atol=1e-9), "directions not unit")
    check(numpy.allclose(direction[:, 2], 0.0, atol=1e-9), "directions not tangent")
    check(faces.min() >= 0 and faces.max() < 800, "FaceId out of range")
    check(placed.GetFieldData().GetArray("Maximal").GetValue(0) == 1.0, "not maximal")

# Outlines: one or more closed polylines per shape; pairwise no crossing, no containment.
def segments_cross(a, b):
    """Any proper crossing between the segments of closed polylines a and b (N x 2 arrays)."""
    p, p2 = a[:-1], a[1:]
    q, q2 = b[:-1], b[1:]
    r = p2 - p
    s = q2 - q
    d = r[:, None, 0] * s[None, :, 1] - r[:, None, 1] * s[None, :, 0]
    qp = q[None, :, :] - p[:, None, :]
    with numpy.errstate(divide="ignore", invalid="ignore"):
        t = (qp[..., 0] * s[None, :, 1] - qp[..., 1] * s[None, :, 0]) / d
        u = (qp[..., 0] * r[:, None, 1] - qp[..., 1] * r[:, None, 0]) / d
    eps = 1e-9
    return bool(numpy.any((numpy.abs(d) > 1e-15) & (t > eps) & (t < 1 - eps) & (u > eps) & (u < 1 - eps)))


def outline_overlaps(outlines):
    """(close pairs, overlapping pairs) of the shapes' drawn outlines (planar, z = 0)."""
    sid = vtk_to_numpy(outlines.GetCellData().GetArray("ShapeId"))
    opts = vtk_to_numpy(outlines.GetPoints().GetData()).astype(float)[:, :2]
    offsets = vtk_to_numpy(outlines.GetLines().GetOffsetsArray())
    conn = vtk_to_numpy(outlines.GetLines().GetConnectivityArray())
    rings = {}
    for c in range(outlines.GetNumberOfCells()):
        rings.setdefault(int(sid[c]), []).append(opts[conn[offsets[c]:offsets[c + 1]]])
    overlaps = 0
    close = 0
    ids = sorted(rings)
    centres = {i: numpy.vstack(rings[i]).mean(axis=0) for i in ids}
    reach = {i: numpy.max(numpy.linalg.norm(numpy.vstack(rings[i]) - centres[i], axis=1)) for i in ids}
    for ia, a in enumerate(ids):
        for b in ids[ia + 1:]:
            if numpy.linalg.norm(centres[a] - centres[b]) > reach[a] + reach[b]:
                continue
            close += 1
            # (a loop, not any(): paraview.simple's star import may shadow the builtin)
            hit = False
            for ra in rings[a]:
                for rb in rings[b]:
                    hit = hit or bool(segments_cross(ra, rb))
            if not hit:
                # containment: a vertex of one inside the other (even-odd over all its rings)
                for (u, v) in ((a, b), (b, a)):
                    p = rings[u][0][0]
                    inside = False
                    for ring in rings[v]:
                        inside ^= bool(inside_polygon(numpy.array([p[0]]), numpy.array([p[1]]), ring[:-1])[0])
                    hit = hit or inside
            overlaps += int(hit)
    return close, overlaps


outlines = fetch(shapes, 2)
check(outlines.GetNumberOfCells() >= n, "fewer outline rings than shapes")
close, overlaps = outline_overlaps(outlines)
print("outline pairs checked", close, "overlaps", overlaps)
check(close > n / 2, "the overlap check saw too few close pairs (%d)" % close)
check(overlaps == 0, "%d overlapping shape pairs" % overlaps)

# VerifyOverlaps: nothing on this result; on deliberately overlapping shapes (stars placed with
# tables shrunk to 75%), the pairs the outline test above finds.
shapes.VerifyOverlaps = 1
verified = fetch(shapes, 0)
check(verified.GetNumberOfPoints() == n, "VerifyOverlaps changed the placements")
pairs_array = verified.GetFieldData().GetArray("OverlappingPairs")
per_shape = verified.GetPointData().GetArray("Overlaps")
check(pairs_array is not None and per_shape is not None, "VerifyOverlaps arrays missing")
if pairs_array is not None and per_shape is not None:
    check(pairs_array.GetValue(0) == 0, "VerifyOverlaps reports %g pairs" % pairs_array.GetValue(0))
    check(vtk_to_numpy(per_shape).max() == 0, "VerifyOverlaps: shapes marked overlapping")
    print("overlap check seconds", verified.GetFieldData().GetArray("OverlapCheckSeconds").GetValue(0),
          "distribution seconds", verified.GetFieldData().GetArray("Seconds").GetValue(0))
shrunk = ProgrammableFilter(Input=msdt, OutputDataSetType="vtkImageData")
shrunk.Script = """
out = self.GetOutput()
out.DeepCopy(self.GetInput())
values = out.GetPointData().GetArray("SafeDistance")
for k in range(values.GetNumberOfTuples()):
    values.SetValue(k, 0.75 * values.GetValue(k))
"""
crowded = ShapeDistributor(Input=density, Table=shrunk, ShapeSize=0.07, Seed=3)
crowded.DirectionArray = ["CELLS", "Direction"]
crowded.DensityArray = ["POINTS", "Density"]
crowded.ClassWeights = [1.0, 0.0]
crowded.DrawnCheck = 0  # the shrunk tables alone decide
crowded.VerifyOverlaps = 1
crowded.UpdatePipeline()
crowd = fetch(crowded, 0)
_, expected = outline_overlaps(fetch(crowded, 2))
found = crowd.GetFieldData().GetArray("OverlappingPairs")
print("deliberate overlaps: outline test", expected, "VerifyOverlaps", found.GetValue(0) if found else None)
check(expected > 10, "shrunk tables should make overlapping stars (%d)" % expected)
if found is not None:
    check(0.9 * expected <= found.GetValue(0) <= expected,
          "VerifyOverlaps found %g of %d overlapping pairs" % (found.GetValue(0), expected))
    marked = vtk_to_numpy(crowd.GetPointData().GetArray("Overlaps"))
    check(marked.sum() == 2 * found.GetValue(0), "Overlaps per shape do not add up to twice the pairs")
Delete(crowded)
Delete(shrunk)
shapes.VerifyOverlaps = 0

decals = fetch(shapes, 1)
check(decals.GetNumberOfCells() > n, "decals too small")
tc = decals.GetPointData().GetTCoords()
check(tc is not None and tc.GetNumberOfComponents() == 2, "decals without texture coordinates")
if tc is not None:
    t = vtk_to_numpy(tc)
    check(t.min() > -1.0 and t.max() < 2.0, "texture coordinates far outside the square")
check(decals.GetCellData().GetArray("ShapeId") is not None, "decals without ShapeId")

# Determinism across thread counts.
shapes.NumberOfThreads = 1
one = vtk_to_numpy(fetch(shapes, 0).GetPoints().GetData()).copy()
shapes.NumberOfThreads = 2
two = vtk_to_numpy(fetch(shapes, 0).GetPoints().GetData()).copy()
check(one.shape == two.shape and numpy.array_equal(one, two), "1 and 2 threads differ")

# FaithfulCheck (advanced): on a plane every shape's map is one-to-one over its silhouette, so
# turning it off changes nothing here (it rejects folded long shapes and large short shapes
# reaching around bumps: TestOverlapCheck).
shapes.FaithfulCheck = 0
unchecked = vtk_to_numpy(fetch(shapes, 0).GetPoints().GetData()).copy()
shapes.FaithfulCheck = 1
check(unchecked.shape == two.shape and numpy.array_equal(unchecked, two),
      "FaithfulCheck changed a planar distribution")

# Modes and MaximumShapes.
shapes.Mode = "Circumcircle Poisson disk"
circles = fetch(shapes, 0).GetNumberOfPoints()
shapes.Mode = "Greedy"
greedy = fetch(shapes, 0).GetNumberOfPoints()
print("circumcircle", circles, "random", n, "greedy", greedy)
check(0 < circles < n, "circumcircle Poisson disk should place fewer shapes than Random")
check(greedy > circles, "greedy should place more shapes than circumcircles")
shapes.Mode = "Random"
shapes.MaximumShapes = 10
check(fetch(shapes, 0).GetNumberOfPoints() == 10, "MaximumShapes not honoured")
shapes.MaximumShapes = 0

# Bad parameters: empty outputs (the errors are printed by VTK).
shapes.ShapeSize = -1.0
check(fetch(shapes, 0).GetNumberOfPoints() == 0, "negative ShapeSize should give no shapes")
shapes.ShapeSize = 0.07
shapes.ClassWeights = [1.0, 2.0, 3.0]
check(fetch(shapes, 0).GetNumberOfPoints() == 0, "wrong number of class weights accepted")
shapes.ClassWeights = [1.0, 1.0]
shapes.DensityArray = ["POINTS", "NoSuchArray"]
check(fetch(shapes, 0).GetNumberOfPoints() == 0, "missing density array accepted")
shapes.DensityArray = ["POINTS", "Density"]

# Render: mesh, outlines and centres.
view = CreateRenderView()
view.ViewSize = [600, 600]
Show(mesh, view)
outlineDisplay = Show(OutputPort(shapes, 2), view)
ColorBy(outlineDisplay, ("CELLS", "ClassId"))
Render(view)
image = os.path.join(temp, "shapes.png")
SaveScreenshot(image, view)
check(os.path.exists(image), "no screenshot")

gs_test.finish()
