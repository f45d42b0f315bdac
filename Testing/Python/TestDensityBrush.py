"""pvpython test: Shape Distributor's density brush as a user sets it (BrushCenter, BrushRadius,
BrushDensity) on the bundled bumpy sphere with the bundled star.

- The brush equals the same factors given as a DensityArray: SVG Geodesic Distance from the
  brush's centre with the distributor's engine (its discrete geodesic graph, truncated at the
  radius), f = max(BrushDensity, min(1, d / BrushRadius)) computed here: the same placements,
  bit for bit; the same again with a density array under the brush (the factors multiply).
- The brush shrinks the shapes: Scale is the brush's factor at each centre (near BrushDensity
  close to the centre, 1 beyond the radius) and there are more shapes than without it.
- The panel shows the brush as ParaView's interactive sphere widget (the proxy's property group
  BrushCenter / BrushRadius with panel_widget InteractiveSphere).
- Bad brush parameters give an error and empty outputs; the next good run works.
- On the planar grid (a boundary) with a long class beside the star: both placed under the brush,
  no overlap of the drawn outlines (VerifyOverlaps).
- Place-keyed candidates: a brush moved, resized and a density edited under it re-decide only
  what they reach, and equal a fresh Shape Distributor's placements and decals bit for bit.

Usage: pvpython TestDensityBrush.py --plugin <GeodesicShapes.so> --data <Data dir>
"""

import numpy
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from paraview.vtk.util.numpy_support import vtk_to_numpy

import gs_test
from gs_test import check

args = gs_test.arguments(plugin=gs_test.REQUIRED, data=gs_test.REQUIRED)


def placements(proxy):
    data = servermanager.Fetch(proxy, idx=0)
    n = data.GetNumberOfPoints()
    if n == 0:
        return {"count": 0}
    points = vtk_to_numpy(data.GetPoints().GetData()).copy()
    arrays = {name: vtk_to_numpy(data.GetPointData().GetArray(name)).copy()
              for name in ("Scale", "ClassId", "Direction", "FaceId")}
    return dict(count=n, points=points, **arrays)


def same(a, b):
    # (paraview.simple's star import shadows the built-in all.)
    return a["count"] == b["count"] and not [
        k for k in a if k != "count" and not numpy.array_equal(a[k], b[k])]


LoadPlugin(args.plugin, remote=False, ns=globals())

mesh = PLYReader(FileNames=[args.data + "/bumpy_sphere.ply"])
msdt = MSDTSource(ShapeFileNames=[args.data + "/shapes/star.png"], AngleBins=24, DistanceSteps=24)
field = CrossField(Input=mesh)
field.UpdatePipeline()
surface = servermanager.Fetch(field)
points = vtk_to_numpy(surface.GetPoints().GetData())
# The brush centre: a little off the surface above a vertex (the filter snaps it).
center = (points[40] * 1.02).tolist()
radius, density = 0.7, 0.25
common = dict(Table=msdt, ShapeSize=0.08, Seed=3, NumberOfThreads=2,
              DirectionArray=["CELLS", "Direction"])  # (the same on every input)

plain = ShapeDistributor(Input=field, **common)
without = placements(plain)

brushed = ShapeDistributor(Input=field, BrushCenter=center, BrushRadius=radius,
                           BrushDensity=density, **common)
with_brush = placements(brushed)
check(with_brush["count"] > without["count"] + 10,
      "the brush adds shapes: %d with it, %d without" % (with_brush["count"], without["count"]))

# The same factors from SVG Geodesic Distance with the distributor's engine (K 50, its DGG of
# accuracy 0.1, truncated at the radius: NaN beyond it, factor 1).
source = PointSource(Center=center, NumberOfPoints=1, Radius=0.0)
distance = SVGGeodesicDistance(Input=field, Sources=source, Solver="DGG (accuracy-bounded)",
                               GraphAccuracy=0.1, MaximumDistance=radius)
factors = ProgrammableFilter(Input=distance, CopyArrays=1)  # (the field's Direction passes)
factors.Script = """
import numpy
d = inputs[0].PointData["GeodesicDistance"]
f = numpy.maximum(%r, numpy.minimum(1.0, d / %r))
output.PointData.append(numpy.where(numpy.isnan(d), 1.0, f), "BrushFactor")
output.PointData.append(0.8 * numpy.where(numpy.isnan(d), 1.0, f), "BrushTimesDensity")
output.PointData.append(numpy.full(len(d), 0.8), "Density")
z = inputs[0].Points[:, 2]
output.PointData.append(numpy.where(z > 0.9, 0.8, 1.0), "Regional")
""" % (density, radius)
factors.UpdatePipeline()
f = vtk_to_numpy(servermanager.Fetch(factors).GetPointData().GetArray("BrushFactor"))
check(abs(f.min() - density) < 0.05 and f.max() == 1.0 and (f < 1.0).sum() > 20,
      "the factors span BrushDensity (%g) .. 1: %g .. %g, %d below 1" % (
          density, f.min(), f.max(), (f < 1.0).sum()))

as_array = ShapeDistributor(Input=factors, DensityArray=["POINTS", "BrushFactor"], **common)
check(same(placements(as_array), with_brush),
      "the brush and its factors given as a DensityArray place the same shapes")

# Scale is the factor at each centre: below 0.5 near the brush's centre, 1 far from it.
scale = with_brush["Scale"]
check(scale.min() < 0.5 and scale.min() >= density - 1e-12 and scale.max() == 1.0,
      "Scale spans the brush's factors: %g .. %g" % (scale.min(), scale.max()))

# Under a density array the factors multiply.
brushed_density = ShapeDistributor(Input=factors, DensityArray=["POINTS", "Density"],
                                   BrushCenter=center, BrushRadius=radius, BrushDensity=density,
                                   **common)
product = ShapeDistributor(Input=factors, DensityArray=["POINTS", "BrushTimesDensity"], **common)
check(same(placements(brushed_density), placements(product)),
      "brush over a DensityArray equals the product of the two as a DensityArray")

# The panel: BrushCenter and BrushRadius form an interactive sphere widget's group.
pdm = servermanager.vtkSMProxyManager.GetProxyManager().GetActiveSessionProxyManager() \
    .GetProxyDefinitionManager()
xml = pdm.GetCollapsedProxyDefinition("filters", "ShapeDistributor", None, True)
widget = None
for i in range(xml.GetNumberOfNestedElements()):
    element = xml.GetNestedElement(i)
    if element.GetName() == "PropertyGroup" and element.GetAttribute("panel_widget"):
        functions = {}
        for j in range(element.GetNumberOfNestedElements()):
            p = element.GetNestedElement(j)
            functions[p.GetAttribute("function")] = p.GetAttribute("name")
        widget = (element.GetAttribute("panel_widget"), functions)
check(widget == ("InteractiveSphere", {"Center": "BrushCenter", "Radius": "BrushRadius"}),
      "the brush's panel group is the sphere widget: %r" % (widget,))

# Bad parameters: errors and empty outputs; then a good run again.
for name, value in (("BrushRadius", -1.0), ("BrushRadius", float("inf")),
                    ("BrushDensity", 0.0), ("BrushDensity", 1.5),
                    ("BrushCenter", [1e6, 0.0, 0.0])):
    setattr(brushed, name, value)
    check(placements(brushed)["count"] == 0, "%s = %r gives an empty output" % (name, value))
    brushed.BrushRadius, brushed.BrushDensity, brushed.BrushCenter = radius, density, center
check(same(placements(brushed), with_brush), "the brush runs again after bad parameters")

# A centre dragged inside the closed surface (here its middle, 1 from every point of the sphere)
# snaps to the closest surface point too.
inside = ShapeDistributor(Input=field, BrushCenter=[0.0, 0.0, 0.0], BrushRadius=radius,
                          BrushDensity=density, **common)
check(placements(inside)["count"] > without["count"], "a brush centred inside the surface")

# On a mesh with a boundary, with a long class (the fish, split into parts, bending with the
# field) beside the star: both classes placed under the brush, no two overlapping by their drawn
# outlines (VerifyOverlaps, independent of the tables).
grid = PLYReader(FileNames=[args.data + "/planar_grid.ply"])
grid_field = CrossField(Input=grid)
two = MSDTSource(ShapeFileNames=[args.data + "/shapes/star.png", args.data + "/shapes/fish.png"],
                 AngleBins=24, DistanceSteps=24)
bounded = ShapeDistributor(Input=grid_field, Table=two, ShapeSize=0.06, Seed=2, NumberOfThreads=2,
                           BrushCenter=[0.5, 0.5, 0.0], BrushRadius=0.35, BrushDensity=0.4,
                           VerifyOverlaps=1)
bounded_data = servermanager.Fetch(bounded, idx=0)
classes = vtk_to_numpy(bounded_data.GetPointData().GetArray("ClassId"))
bounded_scale = vtk_to_numpy(bounded_data.GetPointData().GetArray("Scale"))
pairs = bounded_data.GetFieldData().GetArray("OverlappingPairs").GetValue(0)
check(set(numpy.unique(classes)) == {0, 1} and bounded_scale.min() < 0.6 and pairs == 0,
      "brush on the grid with a long class: classes %s, Scale from %.2f, %d overlapping pairs" % (
          numpy.unique(classes), bounded_scale.min(), pairs))

# Place-keyed candidates: the brush moved, then resized, then a density array under it that
# differs from 1 in one region (the Apply a user makes after each drag): every run re-decides only what the edit reaches
# (IncrementalRun 1, fewer candidates decided than a fresh run) and gives the same placements and
# decals, bit for bit, as a fresh Shape Distributor with the final parameters.


def field_value(data, name):
    return data.GetFieldData().GetArray(name).GetValue(0)


def decal_points(proxy):
    return vtk_to_numpy(servermanager.Fetch(proxy, idx=1).GetPoints().GetData()).copy()


keyed = dict(common, CandidateOrder="Place-keyed (edits re-place what they reach)")
state = dict(BrushCenter=center, BrushRadius=0.3, BrushDensity=0.5)  # (a small edit)
edited = ShapeDistributor(Input=factors, **state, **keyed)
edited.UpdatePipeline()
moved = (points[40] * 0.9 + points[300] * 0.1).tolist()
for step, change in enumerate((dict(BrushCenter=moved), dict(BrushRadius=0.25),
                               dict(DensityArray=["POINTS", "Regional"]))):
    for name, value in change.items():
        setattr(edited, name, value)
    state.update(change)
    edited.UpdatePipeline()
    edited_data = servermanager.Fetch(edited, idx=0)
    fresh = ShapeDistributor(Input=factors, **state, **keyed)
    fresh_data = servermanager.Fetch(fresh, idx=0)
    check(field_value(edited_data, "IncrementalRun") == 1 and
          field_value(fresh_data, "IncrementalRun") == 0,
          "place-keyed edit %d: re-decided what it reached (a share %.3f of the pool)" % (
              step, field_value(edited_data, "EditShare")))
    check(field_value(edited_data, "CandidatesRedecided") <
          0.8 * field_value(fresh_data, "CandidatesRedecided"),
          "place-keyed edit %d: %d candidates decided, %d in a fresh run" % (
              step, field_value(edited_data, "CandidatesRedecided"),
              field_value(fresh_data, "CandidatesRedecided")))
    check(same(placements(edited), placements(fresh)) and
          numpy.array_equal(decal_points(edited), decal_points(fresh)),
          "place-keyed edit %d: the same placements and decals as a fresh run" % step)
    Delete(fresh)

gs_test.finish()
