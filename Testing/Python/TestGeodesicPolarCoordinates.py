"""pvpython test: load the GeodesicShapes plugin and run GeodesicPolarCoordinates as a user would.

On the bundled planar grid (the unit square, normal +z) the geodesic polar coordinates about a
point s are the plane's polar coordinates: rho = |p - s|, theta = atan2(p - s) minus the angle of
the reference direction (counter-clockwise about +z), NaN beyond the radius.

Usage: pvpython TestGeodesicPolarCoordinates.py --plugin <GeodesicShapes.so> --data <Data dir>
"""
import math
import os

import numpy
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from paraview.vtk.util.numpy_support import vtk_to_numpy

import gs_test
from gs_test import check

args = gs_test.arguments(plugin=gs_test.REQUIRED, data=gs_test.REQUIRED)

LoadPlugin(args.plugin, remote=False, ns=globals())
check("GeodesicPolarCoordinates" in globals(),
      "the plugin does not define GeodesicPolarCoordinates")


def fetch(proxy):
    """Output polydata and its arrays (numpy, points in double)."""
    output = servermanager.Fetch(proxy)
    arrays = {}
    for name in ("GeodesicDistance", "PolarAngle", "DecalCoordinates"):
        array = output.GetPointData().GetArray(name)
        arrays[name] = vtk_to_numpy(array).astype(float) if array is not None else None
    points = (vtk_to_numpy(output.GetPoints().GetData()).astype(float)
              if output.GetNumberOfPoints() > 0 else numpy.zeros((0, 3)))
    return output, points, arrays


def check_analytic(name, proxy, centre, zero, radius, decal_size):
    """Compares with the plane's polar coordinates about `centre`, theta's zero at `zero`."""
    output, points, arrays = fetch(proxy)
    rho, theta, decal = (arrays["GeodesicDistance"], arrays["PolarAngle"],
                         arrays["DecalCoordinates"])
    if rho is None or theta is None or decal is None:
        check(False, "%s: missing output arrays" % name)
        return 0
    check(output.GetPointData().GetTCoords() is not None
          and output.GetPointData().GetTCoords().GetName() == "DecalCoordinates",
          "%s: DecalCoordinates are not the active texture coordinates" % name)
    angle_sum = output.GetFieldData().GetArray("SourceAngleSum")
    check(angle_sum is not None and abs(angle_sum.GetValue(0) - 2 * math.pi) < 1e-12,
          "%s: SourceAngleSum is not 2 pi" % name)
    d = points - numpy.asarray(centre, dtype=float)
    distance = numpy.hypot(d[:, 0], d[:, 1])
    beyond = distance > radius + 1e-9
    check(numpy.isnan(rho[beyond]).all() and numpy.isnan(theta[beyond]).all()
          and numpy.isnan(decal[beyond]).all(), "%s: points beyond the radius are not NaN" % name)
    inside = distance < radius - 1e-9
    check(numpy.isfinite(rho[inside]).all(), "%s: points inside the radius are NaN" % name)
    known = numpy.isfinite(rho)
    rho_error = numpy.abs(rho[known] - distance[known]).max()
    away = known & (distance > 1e-12)
    analytic = numpy.arctan2(d[away, 1], d[away, 0]) - zero
    theta_error = numpy.abs(numpy.angle(numpy.exp(1j * (theta[away] - analytic)))).max()
    check(((theta[known] >= 0) & (theta[known] < 2 * math.pi)).all(),
          "%s: PolarAngle outside [0, 2 pi)" % name)
    expected_decal = numpy.column_stack((rho * numpy.cos(theta), rho * numpy.sin(theta)))
    expected_decal = expected_decal / decal_size + 0.5
    decal_error = numpy.abs(decal[known] - expected_decal[known]).max()
    print("%s: %d points inside, rho error %.3g, theta error %.3g, decal error %.3g"
          % (name, known.sum(), rho_error, theta_error, decal_error))
    check(rho_error < 1e-9, "%s: rho differs from |p - s| (%g)" % (name, rho_error))
    check(theta_error < 1e-9, "%s: theta differs from the polar angle (%g)" % (name, theta_error))
    check(decal_error < 1e-12, "%s: DecalCoordinates differ from their formula" % name)
    return int(known.sum())


grid = PLYReader(FileNames=[os.path.join(args.data, "planar_grid.ply")])
grid_points = vtk_to_numpy(servermanager.Fetch(grid).GetPoints().GetData()).astype(float)
centre_id = int(numpy.argmin(numpy.hypot(grid_points[:, 0] - 0.5, grid_points[:, 1] - 0.5)))
centre = grid_points[centre_id]

# 1. Defaults, then a vertex source with ReferenceDirection +x: the plane's polar angle.
polar = GeodesicPolarCoordinates(Input=grid)
check(polar.SourceVertexId == 0, "default SourceVertexId")
check(polar.Radius == 1.0, "default Radius")
check(list(polar.ReferenceDirection) == [0.0, 0.0, 0.0], "default ReferenceDirection")
check(polar.AngleMode == "Geodesic direction", "default AngleMode is %r" % (polar.AngleMode,))
check(polar.DecalSize == 1.0, "default DecalSize")
Delete(polar)

polar = GeodesicPolarCoordinates(Input=grid, SourceVertexId=centre_id, Radius=0.3,
                                 ReferenceDirection=[1, 0, 0], DecalSize=0.6)
inside = check_analytic("vertex source, +x", polar, centre, 0.0, 0.3, 0.6)
check(inside > 100, "too few points inside the radius")

# 2. Change the proxy as a user would: a tilted reference (projected: 45 degrees), larger radius.
polar.ReferenceDirection = [1, 1, 0.5]
polar.Radius = 0.45
check_analytic("vertex source, 45 degrees", polar, centre, math.pi / 4, 0.45, 0.6)

# 3. Default reference: the source's first edge, along a grid edge or diagonal (a multiple of
#    45 degrees); theta is the polar angle up to that offset.
polar.ReferenceDirection = [0, 0, 0]
_, points, arrays = fetch(polar)
east = int(numpy.argmin(numpy.hypot(points[:, 0] - 0.55, points[:, 1] - 0.5)))
zero = -arrays["PolarAngle"][east]
steps = zero / (math.pi / 4)
check(abs(steps - round(steps)) < 1e-9, "first edge at %g rad is not a grid direction" % zero)
check_analytic("vertex source, first edge", polar, centre, zero, 0.45, 0.6)
Delete(polar)

# 4. A point source on the Source port, above the plane: snapped down onto it.
point = PointSource(Center=[0.31, 0.62, 0.2], NumberOfPoints=1, Radius=0.0)
snapped = GeodesicPolarCoordinates(Input=grid, Source=point, Radius=0.25,
                                   ReferenceDirection=[0, 1, 0], DecalSize=0.5)
# The point as the filter sees it (PointSource writes single-precision points).
above = vtk_to_numpy(servermanager.Fetch(point).GetPoints().GetData()).astype(float)[0]
check_analytic("Source port point", snapped, [above[0], above[1], 0.0], math.pi / 2, 0.25, 0.5)
Delete(snapped)

# 5. A curve source (a Line): signed offsets and normalized arc length along the curve.
# (Resolution 6: the line's points fall on mesh vertices, and it runs along mesh edges.)
line = Line(Point1=[0.2, 0.5, 0.0], Point2=[0.8, 0.5, 0.0], Resolution=6)
from_curve = GeodesicPolarCoordinates(Input=grid, Source=line, Radius=0.2)
curve_output = servermanager.Fetch(from_curve)
offset = vtk_to_numpy(curve_output.GetPointData().GetArray("Offset"))
arc = vtk_to_numpy(curve_output.GetPointData().GetArray("ArcLength"))
points = vtk_to_numpy(curve_output.GetPoints().GetData()).astype(float)
beside = (numpy.abs(points[:, 1] - 0.5) < 0.19) & (points[:, 0] > 0.22) & (points[:, 0] < 0.78)
check(beside.sum() > 50, "too few points beside the curve")
print("curve source: %d points beside, offset error %.3g, arc length error %.3g" % (
    beside.sum(), numpy.max(numpy.abs(offset[beside] - (points[beside, 1] - 0.5))),
    numpy.max(numpy.abs(arc[beside] - (points[beside, 0] - 0.2) / 0.6))))
check(numpy.max(numpy.abs(offset[beside] - (points[beside, 1] - 0.5))) < 1e-3,
      "Offset is not the signed distance to the line")
check(numpy.max(numpy.abs(arc[beside] - (points[beside, 0] - 0.2) / 0.6)) < 1e-2,
      "ArcLength is not the fraction along the line")
Delete(from_curve)

# 6. On the curved torus: render once, coloured by PolarAngle, as a user would.
torus = PLYReader(FileNames=[os.path.join(args.data, "torus.ply")])
on_torus = GeodesicPolarCoordinates(Input=torus, SourceVertexId=0, Radius=0.7,
                                    ReferenceDirection=[0, 1, 0], DecalSize=1.4)
_, points, arrays = fetch(on_torus)
rho = arrays["GeodesicDistance"]
known = numpy.isfinite(rho)
check(known.sum() > 100 and rho[known].max() <= 0.7, "torus: points inside the radius")
view = CreateRenderView()
display = Show(on_torus, view)
ColorBy(display, ("POINTS", "PolarAngle"))
Render(view)
Delete(view)
del view

gs_test.finish("all checks passed")
