"""pvpython test: load the GeodesicShapes plugin and run SVGGeodesicDistance as a user would.

Usage: pvpython TestSVGGeodesicDistance.py --plugin <GeodesicShapes.so> --data <Data dir>
"""
import argparse
import math
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from paraview.vtk.util.numpy_support import vtk_to_numpy

parser = argparse.ArgumentParser()
parser.add_argument("--plugin", required=True)
parser.add_argument("--data", required=True)
args = parser.parse_args()

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAILED:", message)


LoadPlugin(args.plugin, remote=False, ns=globals())
check("SVGGeodesicDistance" in globals(), "the plugin does not define SVGGeodesicDistance")

# 1. ParaView spheres, distance from the north pole (point 0) against the great-circle distance
#    R * acos(z / R). The polyhedral distance converges to it as the mesh is refined: check two
#    resolutions, the finer within 0.5% of the half circumference and closer than the coarser.
radius = 2.0


def sphere_error(resolution):
    sphere = Sphere(Radius=radius, ThetaResolution=resolution, PhiResolution=resolution)
    geodesic = SVGGeodesicDistance(Input=sphere, SourceVertexIds=[0])
    check(geodesic.Solver == "SVG (label-correcting)", "default Solver is %r" % (geodesic.Solver,))
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

# 3. Render once, as a user would, to make sure the output displays.
view = CreateRenderView()
display = Show(geodesic, view)
ColorBy(display, ("POINTS", "GeodesicDistance"))
Render(view)
Delete(view)
del view

if failures:
    print("%d failure(s)" % len(failures))
    sys.exit(1)
print("all checks passed")
