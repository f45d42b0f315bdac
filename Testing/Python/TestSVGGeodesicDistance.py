"""pvpython test: load the GeodesicShapes plugin and run SVGGeodesicDistance as a user would.

Usage: pvpython TestSVGGeodesicDistance.py --plugin <GeodesicShapes.so> --data <Data dir>
       [--temp <writable dir>]
"""
import math
import os

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from paraview.vtk.util.numpy_support import vtk_to_numpy

import gs_test
from gs_test import check

args = gs_test.arguments(plugin=gs_test.REQUIRED, data=gs_test.REQUIRED, temp=".")

LoadPlugin(args.plugin, remote=False, ns=globals())
check("SVGGeodesicDistance" in globals(), "the plugin does not define SVGGeodesicDistance")

# 1. ParaView spheres, distance from the north pole (point 0) against the great-circle distance
#    R * acos(z / R). The polyhedral distance converges to it as the mesh is refined: check two
#    resolutions, the finer within 0.5% of the half circumference and closer than the coarser.
radius = 2.0


def sphere_error(resolution):
    sphere = Sphere(Radius=radius, ThetaResolution=resolution, PhiResolution=resolution)
    geodesic = SVGGeodesicDistance(Input=sphere, SourceVertexIds=[0])
    check(geodesic.Solver == "Virtual sources (no precompute)", "default Solver is %r" % (geodesic.Solver,))
    check(geodesic.ResultArrayName == "GeodesicDistance", "default ResultArrayName")
    geodesic.Solver = "Exact"
    output = servermanager.Fetch(geodesic)
    array = output.GetPointData().GetArray("GeodesicDistance")
    check(array is not None, "no GeodesicDistance array")
    if array is None:
        return geodesic, float("inf")
    distance = vtk_to_numpy(array)
    points = vtk_to_numpy(output.GetPoints().GetData())
    check(len(distance) == output.GetNumberOfPoints(), "array size")
    check(distance.min() == 0.0, "distance at the source is not 0")
    check(distance.max() <= 1.001 * math.pi * radius, "distance larger than half circumference")
    worst = 0.0
    for d, p in zip(distance, points):
        great_circle = radius * math.acos(max(-1.0, min(1.0, p[2] / radius)))
        worst = max(worst, abs(d - great_circle))
    print("sphere %dx%d: max |geodesic - great circle| = %.4g (half circumference %.4g)"
          % (resolution, resolution, worst, math.pi * radius))
    return geodesic, worst


_, coarse_error = sphere_error(24)
geodesic, fine_error = sphere_error(64)
check(fine_error < coarse_error, "no convergence to the great-circle distance")

# Changing only the sources re-executes on the cached mesh: the new source has distance 0.
geodesic.SourceVertexIds = [5, 7]
moved = vtk_to_numpy(servermanager.Fetch(geodesic).GetPointData().GetArray("GeodesicDistance"))
check(moved[5] == 0.0 and moved[7] == 0.0 and moved[0] > 0.0, "changing SourceVertexIds")
geodesic.SourceVertexIds = [0]
check(fine_error < 0.005 * math.pi * radius, "sphere distances far from great-circle distances")

# 2. The bundled L-shaped domain read from PLY, two sources given as points on the second port,
#    and a maximum distance: planar, so Euclidean to the nearest source (both sources see the
#    whole disc of radius 0.5 around them) and NaN beyond.
lshape = PLYReader(FileNames=[os.path.join(args.data, "lshape.ply")])
points_source = PointSource(Center=[0.25, 0.375, 0.0], NumberOfPoints=1, Radius=0.0)
geodesic2 = SVGGeodesicDistance(Input=lshape, Sources=points_source, MaximumDistance=0.5,
                                ResultArrayName="dist", Solver="Exact")
output2 = servermanager.Fetch(geodesic2)
array2 = output2.GetPointData().GetArray("dist")
check(array2 is not None, "no 'dist' array")
if array2 is not None:
    distance2 = vtk_to_numpy(array2)
    points2 = vtk_to_numpy(output2.GetPoints().GetData())
    nan_count = 0
    for d, p in zip(distance2, points2):
        euclid = math.hypot(p[0] - 0.25, p[1] - 0.375)
        if euclid < 0.5 - 1e-9:
            check(abs(d - euclid) < 1e-9, "L-shape distance %g != %g at %s" % (d, euclid, p))
        elif euclid > 0.5 + 1e-9:
            nan_count += 1
            check(math.isnan(d), "L-shape distance beyond maximum is %g, not NaN" % d)
    check(nan_count > 0, "no point beyond the maximum distance")

# 3. Each Solver by its name on the bundled torus: the saddle-vertex-graph solvers against the
#    Exact solver (mean relative error < 1e-2 at K = 50), label-correcting == Dijkstra, and the
#    field data describing the graph (built once, then reused from memory).
torus = PLYReader(FileNames=[os.path.join(args.data, "torus.ply")])


def run(proxy):
    output = servermanager.Fetch(proxy)
    array = output.GetPointData().GetArray("GeodesicDistance")
    check(array is not None, "no GeodesicDistance array (Solver %s)" % proxy.Solver)
    return output, (vtk_to_numpy(array) if array is not None else None)


def field_value(output, name):
    array = output.GetFieldData().GetAbstractArray(name)
    return array.GetValue(0) if array is not None and array.GetNumberOfValues() == 1 else None


results = {}
origins = {}
for solver in ["Exact", "SVG (label-correcting)", "SVG (Dijkstra)"]:
    torus_distance = SVGGeodesicDistance(Input=torus, SourceVertexIds=[0, 1000], Solver=solver,
                                         K=50)
    output, results[solver] = run(torus_distance)
    origins[solver] = field_value(output, "SVGGraphOrigin")
    if solver != "Exact":
        degree = field_value(output, "SVGMeanDegree")
        seconds = field_value(output, "SVGBuildSeconds")
        print("%s: graph %s, %.1f links per vertex, built in %.3f s"
              % (solver, origins[solver], degree, seconds))
        check(degree is not None and degree > 6.0, "SVGMeanDegree %r" % (degree,))
        check(seconds is not None and seconds >= 0.0, "SVGBuildSeconds %r" % (seconds,))
    Delete(torus_distance)
check(origins["Exact"] is None, "the Exact solver reports a graph")
check(origins["SVG (label-correcting)"] in ("built", "memory")
      and origins["SVG (Dijkstra)"] == "memory",
      "graph origins %r (the second SVG run must reuse the graph)" % (origins,))
exact = results["Exact"]
if all(r is not None for r in results.values()):
    mask = exact > 1e-9
    for solver in ["SVG (label-correcting)", "SVG (Dijkstra)"]:
        relative = abs(results[solver][mask] - exact[mask]) / exact[mask]
        print("torus, %s vs Exact: mean relative error %.3g, max %.3g"
              % (solver, relative.mean(), relative.max()))
        check(relative.mean() < 1e-2, "%s: mean relative error %g" % (solver, relative.mean()))
    same = abs(results["SVG (label-correcting)"] - results["SVG (Dijkstra)"]).max()
    check(same <= 1e-9, "label-correcting and Dijkstra differ by %g" % same)

# 3b. The accuracy-bounded solver by its name: its largest error within the GraphAccuracy asked for.
dgg = SVGGeodesicDistance(Input=torus, SourceVertexIds=[0, 1000],
                          Solver="DGG (accuracy-bounded)", GraphAccuracy=0.01)
output, distances = run(dgg)
if distances is not None and exact is not None:
    relative = abs(distances[mask] - exact[mask]) / exact[mask]
    print("torus, DGG (accuracy 0.01) vs Exact: mean relative error %.3g, max %.3g, "
          "%.1f links per vertex" % (relative.mean(), relative.max(),
                                     field_value(output, "SVGMeanDegree")))
    check(relative.max() <= 0.01, "DGG: largest relative error %g above the accuracy"
          % relative.max())
Delete(dgg)

# 4. Curve sources on the bundled planar grid (unit square): a PolyLineSource (two segments) and
#    a Line source, against the analytic distance to the polyline, for each Solver.
grid = PLYReader(FileNames=[os.path.join(args.data, "planar_grid.ply")])


def distance_to_polyline(p, polyline):
    best = float("inf")
    for (ax, ay), (bx, by) in zip(polyline[:-1], polyline[1:]):
        dx, dy = bx - ax, by - ay
        t = max(0.0, min(1.0, ((p[0] - ax) * dx + (p[1] - ay) * dy) / (dx * dx + dy * dy)))
        best = min(best, math.hypot(p[0] - ax - t * dx, p[1] - ay - t * dy))
    return best


bent = [(0.23, 0.31), (0.61, 0.47), (0.78, 0.83)]
polyline = PolyLineSource(Points=[c for x, y in bent for c in (x, y, 0.0)])
line = Line(Point1=[0.12, 0.74, 0.0], Point2=[0.87, 0.21, 0.0], Resolution=3)
for name, curve_source, curve in [("PolyLineSource", polyline, bent),
                                  ("Line", line, [(0.12, 0.74), (0.87, 0.21)])]:
    for solver in ["Exact", "SVG (label-correcting)", "SVG (Dijkstra)"]:
        from_curve = SVGGeodesicDistance(Input=grid, Sources=curve_source, Solver=solver)
        output, distance = run(from_curve)
        if distance is not None:
            points = vtk_to_numpy(output.GetPoints().GetData())
            errors = []
            for d, p in zip(distance, points):
                analytic = distance_to_polyline(p, curve)
                if analytic > 1e-9:
                    errors.append(abs(d - analytic) / analytic)
            mean = sum(errors) / max(1, len(errors))
            print("curve %s, %s: mean relative error %.3g over %d points"
                  % (name, solver, mean, len(errors)))
            check(len(errors) > 400 and mean < 1e-2,
                  "curve %s, %s: mean relative error %g" % (name, solver, mean))
        Delete(from_curve)

# 5. CacheFileName: the graph is written there (the C++ test covers loading and bad files).
cache_file = os.path.join(args.temp, "TestSVGGeodesicDistance_grid.svgg")
if os.path.exists(cache_file):
    os.remove(cache_file)
cached = SVGGeodesicDistance(Input=grid, SourceVertexIds=[0], Solver="SVG (label-correcting)", K=30,
                             CacheFileName=cache_file,
                             UnfoldingRefinement=1)
output, distance = run(cached)
check(os.path.exists(cache_file), "CacheFileName: %s was not written" % cache_file)
if distance is not None:
    # On a plane the unfolding refinement is exact.
    points = vtk_to_numpy(output.GetPoints().GetData())
    worst = max(abs(d - math.hypot(p[0] - points[0][0], p[1] - points[0][1]))
                for d, p in zip(distance, points))
    check(worst < 1e-9, "UnfoldingRefinement on the plane: error %g" % worst)
Delete(cached)
if os.path.exists(cache_file):
    os.remove(cache_file)

# 6. Render once, as a user would, to make sure the output displays.
view = CreateRenderView()
display = Show(geodesic, view)
ColorBy(display, ("POINTS", "GeodesicDistance"))
Render(view)
Delete(view)
del view

gs_test.finish("all checks passed")
