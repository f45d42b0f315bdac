"""pvpython test: load the GeodesicShapes plugin and run MSDTSource as a user would.

Shapes are written by the test (numpy + vtkPNGWriter): a disk (RGBA, alpha silhouette) and a
6:1 bar (grey, luminance silhouette, split into 3 parts). The three outputs are fetched and
checked against what the shapes imply. When the openclipart-png silhouettes (star, eagle, fish)
are installed, they are run as well; otherwise that part is skipped with a message.

Usage: pvpython TestMSDTSource.py --plugin <GeodesicShapes.so> [--temp <writable dir>]
       [--clipart <openclipart png dir>]
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

args = gs_test.arguments(plugin=gs_test.REQUIRED, temp=None, clipart="/usr/share/openclipart/png")


def write_png(path, inside, rgba):
    """inside: boolean array [row, column], row 0 at the BOTTOM (VTK image order)."""
    height, width = inside.shape
    if rgba:
        pixels = numpy.zeros((height, width, 4), dtype=numpy.uint8)
        pixels[..., 3] = numpy.where(inside, 255, 0)  # black, opaque inside
    else:
        pixels = numpy.where(inside, 0, 255).astype(numpy.uint8)[..., None]  # dark inside
    image = vtkImageData()
    image.SetDimensions(width, height, 1)
    array = numpy_to_vtk(pixels.reshape(width * height, -1), deep=True)
    array.SetName("pixels")
    image.GetPointData().SetScalars(array)
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputData(image)
    writer.Write()


def field(data, name):
    array = data.GetFieldData().GetArray(name)
    check(array is not None, "no field data array %s" % name)
    return vtk_to_numpy(array) if array is not None else None


LoadPlugin(args.plugin, remote=False, ns=globals())
check("MSDTSource" in globals(), "the plugin does not define MSDTSource")

# 0. MSDT Source is a source (issue 20): made while another source is active it has no input
# and takes none, and it says nothing before its properties are set; asked for its output
# without a shape, it says what to set. The polygons route is the filter MSDT From Polygons.
from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow

messages = vtkStringOutputWindow()
previous_window = vtkOutputWindow.GetInstance()
vtkOutputWindow.SetInstance(messages)
sphere = Sphere()
SetActiveSource(sphere)
bare = MSDTSource()
check(bare.GetProperty("Polygons") is None and bare.GetProperty("Input") is None,
      "MSDT Source has an input property")
bare.AngleBins = 16
check(messages.GetOutput() == "", "messages before the properties are set: %r" % messages.GetOutput())
bare.UpdatePipeline()
check("No shape" in messages.GetOutput() and "ShapeFileNames" in messages.GetOutput(),
      "no shape: %r" % messages.GetOutput())
check(bare.GetDataInformation(0).GetNumberOfPoints() == 0, "no shape: output not empty")
SetActiveSource(sphere)
check("MSDTFromPolygons" in globals(), "the plugin does not define MSDTFromPolygons")
polygons_filter = MSDTFromPolygons()
check(polygons_filter.Input is not None and polygons_filter.Input.SMProxy == sphere.SMProxy,
      "MSDT From Polygons does not take the active source as its input")
vtkOutputWindow.SetInstance(previous_window)
Delete(polygons_filter)
Delete(bare)
Delete(sphere)

temp = tempfile.mkdtemp(prefix="TestMSDTSource_", dir=args.temp)
size = 64
y, x = numpy.mgrid[0:size, 0:size] + 0.5
disk = numpy.hypot(x - 32, y - 32) <= 20
bar = (numpy.abs(x - 32) < 24) & (numpy.abs(y - 32) < 4)  # 48 x 8 pixels
disk_file = os.path.join(temp, "disk.png")
bar_file = os.path.join(temp, "bar.png")
write_png(disk_file, disk, rgba=True)
write_png(bar_file, bar, rgba=False)

# 1. Two image shapes, as a user would.
ka, kr, ts = 16, 32, 64
msdt = MSDTSource(ShapeFileNames=[disk_file, bar_file], AngleBins=ka, DistanceSteps=kr,
                  TextureSize=ts)
check(msdt.MaximumAspectRatio == 2 and msdt.AlphaThreshold == 0.5, "defaults")
tables = servermanager.Fetch(msdt, idx=0)
outlines = servermanager.Fetch(msdt, idx=1)
textures = servermanager.Fetch(msdt, idx=2)

# Tables: P = 1 (disk) + 3 (bar parts) = 4 parts, 16 tables.
check(tables.GetDimensions() == (ka, ka, 16), "table dimensions %r" % (tables.GetDimensions(),))
check(tuple(msdt.GetDataInformation(0).GetExtent()) == (0, ka - 1, 0, ka - 1, 0, 15),
      "whole extent seen by the client %r" % (msdt.GetDataInformation(0).GetExtent(),))
values_array = tables.GetPointData().GetArray("SafeDistance")
check(values_array is not None, "no SafeDistance array")
values = vtk_to_numpy(values_array).reshape(16, ka, ka) if values_array else None
parts = field(tables, "ClassNumberOfParts")
radius = field(tables, "PartRadius")
step = field(tables, "PairDistanceStep")
check(parts is not None and list(parts) == [1, 3], "ClassNumberOfParts %r" % (parts,))
check(field(tables, "ClassRadius")[0] == 1.0, "the first class has radius 1")
if values is not None and radius is not None and step is not None:
    print("SafeDistance range %.4f .. %.4f" % (values.min(), values.max()))
    for pair in range(16):
        a, b = divmod(pair, 4)
        bound = radius[a] + radius[b]
        check(values[pair].max() <= bound + 1e-12 and values[pair].min() > 0.0,
              "pair %d outside (0, r_a + r_b]" % pair)
        check(abs(step[pair] - bound / kr) < 1e-12, "PairDistanceStep of pair %d" % pair)
    # Disk against disk: 2 within one step everywhere.
    check(numpy.all(numpy.abs(values[0] - 2.0) <= step[0] + 1e-12), "disk table is not 2")
    # Bar part against itself varies with the angles: side by side (both vertical, i.e. at
    # 90 degrees to the line of centres) is closer than end to end (both at 0 degrees).
    middle = 1 + 1  # the bar's middle part
    pair = middle * 4 + middle
    check(values[pair, ka // 4, ka // 4] < values[pair, 0, 0],
          "bar middle part: side by side %.3f vs end to end %.3f"
          % (values[pair, ka // 4, ka // 4], values[pair, 0, 0]))
names = tables.GetFieldData().GetAbstractArray("ClassName")
check(names is not None and names.GetValue(1) == bar_file, "ClassName")

# Outlines: one closed polyline per contour, ClassId 0 (disk) and 1 (bar), centred.
check(outlines.GetNumberOfCells() == 2, "outline cells %d" % outlines.GetNumberOfCells())
class_id = outlines.GetCellData().GetArray("ClassId")
check(class_id is not None and sorted(vtk_to_numpy(class_id)) == [0, 1], "ClassId")
if class_id is not None and outlines.GetNumberOfCells() == 2:
    points = vtk_to_numpy(outlines.GetPoints().GetData())
    for cell in range(2):
        ids = outlines.GetCell(cell).GetPointIds()
        ring = numpy.array([points[ids.GetId(k)] for k in range(ids.GetNumberOfIds())])
        check(numpy.allclose(ring[0], ring[-1]), "outline %d is not closed" % cell)
        half = (ring.max(axis=0) - ring.min(axis=0))[:2] / 2
        centre = (ring.max(axis=0) + ring.min(axis=0))[:2] / 2
        check(numpy.allclose(centre, 0.0, atol=1e-9), "outline %d not centred" % cell)
        if vtk_to_numpy(class_id)[cell] == 1:
            # The bar: 48 x 8 pixels in units of the disk's radius (about 20 pixels).
            scale = 1.0 / field(tables, "Scale")[0]
            check(numpy.allclose(half, [24 * scale, 4 * scale], rtol=1e-9),
                  "bar outline half sizes %r" % (half,))

# Silhouettes: ts x ts, one component per class; the inside fraction of the square around
# each class's circle is its pixel count over (2 r)^2 (r: its circumradius in pixels).
check(textures.GetDimensions() == (ts, ts, 1), "texture dimensions")
texels_array = textures.GetPointData().GetArray("Silhouette")
check(texels_array is not None and texels_array.GetNumberOfComponents() == 2, "Silhouette")
if texels_array is not None:
    texels = vtk_to_numpy(texels_array).reshape(ts, ts, 2)
    check(set(numpy.unique(texels)) <= {0, 255}, "texels are not 0 / 255")
    fractions = (texels == 255).mean(axis=(0, 1))
    pixel_radius = field(tables, "ClassRadius") * field(tables, "Scale")[0]
    check(abs(pixel_radius[1] - math.hypot(24, 4)) < 1e-9, "bar radius %g" % pixel_radius[1])
    expected = [disk.sum() / (2 * pixel_radius[0]) ** 2, bar.sum() / (2 * pixel_radius[1]) ** 2]
    print("texture inside fractions %s, expected %s" % (fractions, expected))
    check(numpy.allclose(fractions, expected, atol=0.03), "texture inside fractions")
    check(texels[ts // 2, ts // 2, 0] == 255 and texels[0, 0, 0] == 0, "disk texture")

# Changing only the tables' resolution keeps the shapes (no new read) and the new extent shows.
msdt.AngleBins = 8
msdt.UpdatePipeline()
check(tuple(msdt.GetDataInformation(0).GetExtent()) == (0, 7, 0, 7, 0, 15), "AngleBins = 8")

# 2. A closed polyline (a triangle) through MSDT From Polygons, after the images: a third class.
triangle = PolyLineSource(Points=[0, 0, 0, 30, 0, 0, 0, 30, 0], Closed=1)
from_polygons = MSDTFromPolygons(Input=triangle, ShapeFileNames=list(msdt.ShapeFileNames),
                                 AngleBins=8)
from_polygons.UpdatePipeline()
with_polygon = servermanager.Fetch(from_polygons, idx=0)
parts = field(with_polygon, "ClassNumberOfParts")
check(parts is not None and list(parts) == [1, 3, 1], "with a polygon: parts %r" % (parts,))
check(with_polygon.GetDimensions() == (8, 8, 25), "with a polygon: %r"
      % (with_polygon.GetDimensions(),))

# 3. Render once, as a user would: the outlines and the silhouettes.
view = CreateRenderView()
Show(OutputPort(msdt, 1), view)
Show(OutputPort(msdt, 2), view)
Render(view)
Delete(view)
del view
Delete(from_polygons)
Delete(msdt)
Delete(triangle)

# 4. Optional: the openclipart silhouettes (package openclipart-png).
clipart = {
    "star": os.path.join(args.clipart, "shapes", "star_double_tom_webb_.png"),
    "eagle": os.path.join(args.clipart, "animals", "birds", "eagle_01.png"),
    "fish": os.path.join(args.clipart, "animals", "fish", "yellow_gourami_01.png"),
}
missing = [path for path in clipart.values() if not os.path.exists(path)]
if missing:
    print("SKIPPED the openclipart check: missing %s (apt-get install openclipart-png)"
          % ", ".join(missing))
else:
    shapes = MSDTSource(ShapeFileNames=list(clipart.values()), AngleBins=32, DistanceSteps=32)
    result = servermanager.Fetch(shapes, idx=0)
    parts = field(result, "ClassNumberOfParts")
    aspect = field(result, "ClassAspectRatio")
    print("openclipart star, eagle, fish: aspect ratios %s, parts %s" % (aspect, parts))
    if parts is not None and aspect is not None:
        for k in range(3):
            check(parts[k] == max(1, math.ceil(aspect[k] / 2.0 - 1e-12)),
                  "clipart class %d: %d parts for aspect %.3f" % (k, parts[k], aspect[k]))
        check(parts[2] >= 2, "the fish (long) is not split")
        count = int(parts.sum())
        check(result.GetDimensions() == (32, 32, count * count), "clipart table dimensions")
        values = vtk_to_numpy(result.GetPointData().GetArray("SafeDistance"))
        values = values.reshape(count * count, 32 * 32)
        radius = field(result, "PartRadius")
        bounds = numpy.array([radius[a] + radius[b] for a in range(count) for b in range(count)])
        check(numpy.all(values.max(axis=1) <= bounds + 1e-12) and values.min() > 0.0,
              "clipart tables outside (0, r_a + r_b]")
        # Not round: the tables vary (at least 10% between their extremes).
        check(numpy.all(values.min(axis=1) < 0.9 * values.max(axis=1)), "flat clipart table")
    outlines = servermanager.Fetch(shapes, idx=1)
    ids = vtk_to_numpy(outlines.GetCellData().GetArray("ClassId"))
    check(sorted(set(ids)) == [0, 1, 2], "clipart outlines ClassId")
    textures = servermanager.Fetch(shapes, idx=2)
    check(textures.GetPointData().GetArray("Silhouette").GetNumberOfComponents() == 3,
          "clipart textures")
    Delete(shapes)

for path in (disk_file, bar_file):
    os.remove(path)
os.rmdir(temp)
gs_test.finish("all checks passed")
