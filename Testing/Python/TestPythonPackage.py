"""Plain python3 test (not pvpython) of the package geodesicshapes (issue 20).

1. The five filters as VTK classes in a plain VTK pipeline: vtkPLYReader -> filter -> numpy.
2. The numpy functions, with meshes as (vertices, triangles) arrays, against exact answers:
   distances and polar coordinates on a plane (Euclidean), the singularity indices of a field on
   a sphere (Euler characteristic), the disk-disk safe distance (2), a distribution checked by
   its drawn outlines; errors raise GeodesicShapesError with the filter's message.

Usage: python3 TestPythonPackage.py --data <Data folder>  (PYTHONPATH: the package's folder)
"""
import math
import warnings

import numpy

import geodesicshapes as gs
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow
from vtkmodules.vtkIOPLY import vtkPLYReader

import gs_test
from gs_test import check

args = gs_test.arguments(data=gs_test.REQUIRED)

# Messages of filters run through the functions must not reach the output window.
messages = vtkStringOutputWindow()
vtkOutputWindow.SetInstance(messages)

# 1. The VTK classes in a plain VTK pipeline.
reader = vtkPLYReader()
reader.SetFileName(args.data + "/bumpy_sphere.ply")
distance = gs.vtkSVGGeodesicDistance()
distance.SetInputConnection(reader.GetOutputPort())
distance.AddSourceVertexId(0)
distance.Update()
d = vtk_to_numpy(distance.GetOutput().GetPointData().GetArray("GeodesicDistance"))
check(d.shape == (2562,) and d[0] == 0.0 and 2.5 < numpy.nanmax(d) < 3.5,
      "vtkSVGGeodesicDistance: %s, max %s" % (d.shape, numpy.nanmax(d)))

polar = gs.vtkGeodesicPolarCoordinates()
polar.SetInputConnection(reader.GetOutputPort())
polar.SetSourceVertexId(0)
polar.SetRadius(0.5)
polar.Update()
rho = vtk_to_numpy(polar.GetOutput().GetPointData().GetArray("GeodesicDistance"))
check(numpy.nanmax(rho) <= 0.5 + 1e-12 and numpy.isnan(rho).any(), "vtkGeodesicPolarCoordinates")

field = gs.vtkCrossField()
field.SetInputConnection(reader.GetOutputPort())
field.SetSymmetry(1)
tables = gs.vtkMSDTSource()
tables.AddShapeFileName(args.data + "/shapes/star.png")
tables.SetAngleBins(32)
tables.SetDistanceSteps(32)
shapes = gs.vtkShapeDistributor()
shapes.SetInputConnection(0, field.GetOutputPort())
shapes.SetInputConnection(1, tables.GetOutputPort(0))
shapes.SetShapeSize(0.08)
shapes.SetSeed(3)
shapes.Update()
placements = shapes.GetOutput(0)
index = vtk_to_numpy(field.GetOutput().GetPointData().GetArray("SingularityIndex"))
check(abs(index.sum() - 2.0) < 1e-9, "vtkCrossField: index sum %s" % index.sum())
check(tables.GetOutputDataObject(0).GetDimensions() == (32, 32, 1), "vtkMSDTSource: %r" % (tables.GetOutputDataObject(0).GetDimensions(),))
n_pipeline = placements.GetNumberOfPoints()
check(n_pipeline > 300, "vtkShapeDistributor: %d shapes" % n_pipeline)
check(shapes.GetOutput(1).GetNumberOfCells() > 0 and shapes.GetOutput(2).GetNumberOfCells() > 0,
      "vtkShapeDistributor: empty decals or outlines")
print("VTK pipeline: distance max %.3f, %d shapes" % (numpy.nanmax(d), n_pipeline))

# 2. The numpy functions.
sphere = reader.GetOutput()
V, F = gs.points_of(sphere), gs.triangles_of(sphere)
check(V.shape == (2562, 3) and F.shape == (5120, 3), "points_of / triangles_of")

# A plane: distances and polar coordinates are Euclidean.
n = 21
x, y = numpy.meshgrid(numpy.linspace(-1, 1, n), numpy.linspace(-1, 1, n))
plane_v = numpy.column_stack([x.ravel(), y.ravel(), numpy.zeros(n * n)])
quads = [(j * n + i, j * n + i + 1, (j + 1) * n + i + 1, (j + 1) * n + i)
         for j in range(n - 1) for i in range(n - 1)]
plane_f = numpy.array([t for a, b, c, e in quads for t in ((a, b, c), (a, c, e))])
centre = (n * n) // 2
euclid = numpy.linalg.norm(plane_v - plane_v[centre], axis=1)
for solver in ("svg", "svg-dijkstra", "dgg", "exact", "virtual sources"):
    g = gs.geodesic_distance((plane_v, plane_f), centre, solver=solver)
    check(numpy.allclose(g, euclid, atol=1e-9), "geodesic_distance %s on a plane: off by %g"
          % (solver, numpy.abs(g - euclid).max()))
# The discrete geodesic graph with reached stencils: exact on the plane too, and closer than
# the links-only stencils on the sphere (against the exact solver).
g = gs.geodesic_distance((plane_v, plane_f), centre, solver="dgg", graph_accuracy=0.1, reached_stencil=True)
check(numpy.allclose(g, euclid, atol=1e-9), "dgg reached_stencil on a plane: off by %g"
      % numpy.abs(g - euclid).max())
exact_sphere = gs.geodesic_distance((V, F), 7, solver="exact")
mean_error = {}
for reached in (False, True):
    d = gs.geodesic_distance((V, F), 7, solver="dgg", graph_accuracy=0.1, reached_stencil=reached)
    far = exact_sphere > 0
    mean_error[reached] = numpy.mean(numpy.abs(d[far] - exact_sphere[far]) / exact_sphere[far])
print("dgg accuracy 0.1 on the sphere: mean relative error %.3g with reached_stencil, %.3g without"
      % (mean_error[True], mean_error[False]))
check(mean_error[True] < 0.75 * mean_error[False], "reached_stencil mean error %g, links-only %g"
      % (mean_error[True], mean_error[False]))
# From a point between vertices and from a curve (the x axis: distance |y|).
point = numpy.array([[0.05, 0.02, 0.0]])
g = gs.geodesic_distance((plane_v, plane_f), point, solver="exact")
check(numpy.allclose(g, numpy.linalg.norm(plane_v - point[0], axis=1), atol=1e-9), "distance from a point")
g = gs.geodesic_distance((plane_v, plane_f), curves=[numpy.array([[-1.0, 0, 0], [1.0, 0, 0]])], solver="exact")
check(numpy.allclose(g, numpy.abs(plane_v[:, 1]), atol=1e-9), "distance from a curve")
pc = gs.polar_coordinates((plane_v, plane_f), centre, 0.6, reference_direction=(1, 0, 0))
inside = euclid <= 0.6 - 1e-9
check(numpy.allclose(pc.rho[inside], euclid[inside], atol=1e-9), "polar rho")
angles = numpy.mod(numpy.arctan2(plane_v[:, 1] - plane_v[centre, 1], plane_v[:, 0] - plane_v[centre, 0]), 2 * math.pi)
far = inside & (euclid > 1e-9)
diff = numpy.abs(numpy.angle(numpy.exp(1j * (pc.theta[far] - angles[far]))))
check(diff.max() < 1e-9, "polar theta off by %g" % diff.max())
check(numpy.isnan(pc.rho[euclid > 0.6 + 1e-9]).all(), "polar beyond the radius")
curve = gs.polar_coordinates((plane_v, plane_f), numpy.array([[-0.5, 0, 0], [0.5, 0, 0]]), 0.3)
check(curve.offset is not None and numpy.nanmax(numpy.abs(curve.offset)) <= 0.3 + 1e-9, "curve coordinates")

# A field on the sphere: indices add up to the Euler characteristic; prescribed ones are kept.
cf = gs.cross_field((V, F), symmetry=4)
check(cf.face_directions.shape == (5120, 3) and abs(cf.singularity_index.sum() - 2.0) < 1e-9,
      "cross_field: %s, index sum %s" % (cf.face_directions.shape, cf.singularity_index.sum()))
poles = numpy.array([V[numpy.argmax(V[:, 2])], V[numpy.argmin(V[:, 2])]])
cf1 = gs.cross_field((V, F), symmetry=1, singularities=(poles, [1.0, 1.0]))
top = numpy.argmax(V[:, 2])
check(abs(cf1.singularity_index[top] - 1.0) < 1e-9, "prescribed singularity at the pole")

# Tables of polygons: a disk against itself is 2 within a step everywhere.
disk = numpy.column_stack([numpy.cos(numpy.linspace(0, 2 * math.pi, 200, endpoint=False)),
                           numpy.sin(numpy.linspace(0, 2 * math.pi, 200, endpoint=False))])
t = gs.safe_distance_tables(polygons=[disk], angle_bins=16, distance_steps=64)
check(t.values.shape == (1, 16, 16) and numpy.all(numpy.abs(t.values - 2.0) <= 2.0 / 64 + 1e-9),
      "disk tables: %s, %s..%s" % (t.values.shape, t.values.min(), t.values.max()))
star = gs.safe_distance_tables([args.data + "/shapes/star.png", args.data + "/shapes/fish.png"],
                               angle_bins=32, distance_steps=32)
check(list(star.class_parts) == [1, 2] and star.values.shape == (9, 32, 32),
      "star + fish tables: parts %s, %s" % (star.class_parts, star.values.shape))

# A distribution on (vertices, triangles): deterministic, conflict-free by its drawn outlines.
dist = gs.distribute_shapes((V, F), star, seed=5, verify_overlaps=True)
again = gs.distribute_shapes((V, F), star, seed=5, threads=1)
check(len(dist) > 100 and numpy.array_equal(dist.positions, again.positions),
      "distribute_shapes: %d shapes, same for 1 thread: %s" % (len(dist), numpy.array_equal(dist.positions, again.positions)))
check(dist.overlapping_pairs == 0, "overlapping pairs: %s" % dist.overlapping_pairs)
check(abs(dist.shape_size - 0.04 * numpy.ptp(V, axis=0).max()) < 1e-9, "automatic size %s" % dist.shape_size)
check(set(numpy.unique(dist.class_ids)) == {0, 1}, "classes %s" % numpy.unique(dist.class_ids))
normal_dot = numpy.abs((dist.directions * dist.normals).sum(axis=1)).max()
check(normal_dot < 1e-6, "directions are tangent (%g)" % normal_dot)
# Per-face and per-vertex directions, and a density.
faces_dir = numpy.tile([1.0, 0.0, 0.0], (len(F), 1))
by_face = gs.distribute_shapes((V, F), star, directions=faces_dir, size=0.1, seed=2)
by_vertex = gs.distribute_shapes((V, F), star, directions=numpy.tile([1.0, 0.0, 0.0], (len(V), 1)), size=0.1, seed=2)
dense = gs.distribute_shapes((V, F), star, directions=faces_dir, size=0.1, seed=2,
                             density=numpy.full(len(V), 0.5))
check(len(by_face) > 50 and len(by_vertex) > 50, "directions per face / vertex: %d, %d" % (len(by_face), len(by_vertex)))
check(3.0 < len(dense) / len(by_face) < 5.0, "density 0.5: %d against %d" % (len(dense), len(by_face)))
# The density brush equals its factors, computed here from geodesic_distance with the
# distributor's engine (its DGG of accuracy 0.1, truncated at the radius), given as a density.
brush_centre, radius = V[7] * 1.01, 0.6
brushed = gs.distribute_shapes((V, F), star, directions=faces_dir, size=0.1, seed=2,
                               brush=(brush_centre, radius, 0.25))
d = gs.geodesic_distance((V, F), [brush_centre], solver="dgg", graph_accuracy=0.1, maximum_distance=radius)
factors = numpy.where(numpy.isfinite(d), numpy.maximum(0.25, numpy.minimum(1.0, d / radius)), 1.0)
as_density = gs.distribute_shapes((V, F), star, directions=faces_dir, size=0.1, seed=2,
                                  density=factors)
check(len(brushed) > len(by_face) and numpy.array_equal(brushed.positions, as_density.positions),
      "brush: %d shapes (%d without), the same as its factors as a density: %s" % (
          len(brushed), len(by_face), numpy.array_equal(brushed.positions, as_density.positions)))
for bad in ((brush_centre, radius), (brush_centre[:2], radius, 0.25), "brush"):
    try:
        gs.distribute_shapes((V, F), star, brush=bad)
        check(False, "brush=%r accepted" % (bad,))
    except ValueError:
        pass
print("functions: %d shapes (automatic size %.3f), %d / %d with given directions, %d at density 0.5"
      % (len(dist), dist.shape_size, len(by_face), len(by_vertex), len(dense)))

# Progress: fractions that rise to 1 through the phases; False aborts (no result, the next call
# runs whole).
seen = []
with_progress = gs.distribute_shapes((V, F), star, seed=5, progress=seen.append)
check(numpy.array_equal(with_progress.positions, dist.positions), "progress changed the result")
check(len(seen) >= 3 and seen[-1] == 1.0 and all(b >= a for a, b in zip(seen, seen[1:])),
      "progress fractions: %s" % seen)
distance_seen = []
gs.geodesic_distance((V, F), 0, progress=distance_seen.append)
check(distance_seen and distance_seen[-1] == 1.0, "geodesic_distance progress: %s" % distance_seen)
asked = []


def stop_after_start(fraction):
    asked.append(fraction)
    return fraction == 0.0


try:
    gs.distribute_shapes((V, F), star, seed=5, progress=stop_after_start)
    check(False, "progress returning False did not abort")
except gs.GeodesicShapesAborted as e:
    check("aborted" in str(e) and len(asked) >= 2 and max(asked) < 1.0,
          "abort: %r after %s" % (str(e), asked))
check(isinstance(gs.GeodesicShapesAborted("x"), gs.GeodesicShapesError), "Aborted is an Error")
again_whole = gs.distribute_shapes((V, F), star, seed=5)
check(numpy.array_equal(again_whole.positions, dist.positions), "a call after an abort differs")
try:
    gs.distribute_shapes((V, F), star, progress=0.5)
    check(False, "a non-callable progress accepted")
except TypeError as e:
    check("progress" in str(e), "non-callable progress: %r" % str(e))
print("progress: %d reports (%s ... %s), abort after %d" % (len(seen), seen[0], seen[-1], len(asked)))

# Errors: the filters' messages as exceptions, bad arguments as Python errors.
def raises(kind, function, *a, **k):
    try:
        function(*a, **k)
    except kind as e:
        return str(e)
    return None


text = raises(gs.GeodesicShapesError, gs.distribute_shapes, (V, F), star, size=-1.0)
check(text is not None and "ShapeSize" in text, "negative size: %r" % text)
text = raises(gs.GeodesicShapesError, gs.geodesic_distance, (V, F), 10 ** 6)
check(text is not None and "10000" in text or (text is not None and "vertex" in text.lower()), "bad source: %r" % text)
text = raises(gs.GeodesicShapesError, gs.safe_distance_tables, ["/nonexistent.png"])
check(text is not None and "nonexistent" in text, "unreadable image: %r" % text)
bad = V.copy()
bad[3] = numpy.nan
text = raises(gs.GeodesicShapesError, gs.cross_field, (bad, F))
check(text is not None, "NaN coordinates: %r" % text)
check(raises(ValueError, gs.as_polydata, (V, F[:, :2])) is not None, "(m, 2) triangles accepted")
check(raises(ValueError, gs.as_polydata, (V, F + len(V))) is not None, "out-of-range indices accepted")
check(raises(TypeError, gs.as_polydata, "mesh.ply") is not None, "a file name accepted as a mesh")
check(raises(ValueError, gs.distribute_shapes, (V, F), star, directions=numpy.zeros((7, 3))) is not None,
      "wrong number of directions accepted")
# Radius 0 or NaN names Radius (not DecalSize, which the caller never set); an infinite radius
# is the whole surface.
for bad_radius in (0.0, float("nan"), -1.0):
    text = raises(gs.GeodesicShapesError, gs.polar_coordinates, (plane_v, plane_f), centre, bad_radius)
    check(text is not None and "Radius must be > 0" in text and "DecalSize" not in text,
          "polar_coordinates(radius=%r): %r" % (bad_radius, text))
whole = gs.polar_coordinates((plane_v, plane_f), centre, float("inf"))
check(numpy.isfinite(whole.rho).all() and numpy.allclose(whole.rho, euclid, atol=1e-9),
      "polar_coordinates(radius=inf)")
# MaximumDistance negative or NaN is an error naming it.
for bad_limit in (-1.0, float("nan")):
    text = raises(gs.GeodesicShapesError, gs.geodesic_distance, (plane_v, plane_f), 0,
                  maximum_distance=bad_limit)
    check(text is not None and "MaximumDistance" in text, "maximum_distance=%r: %r" % (bad_limit, text))
# cache_file pointing at a user's file: an error naming it, the file untouched.
import os
import tempfile
with tempfile.TemporaryDirectory() as folder:
    users = os.path.join(folder, "my_mesh.ply")
    with open(users, "w") as out:
        out.write("ply\nformat ascii 1.0\nelement vertex 0\nend_header\n")
    before = open(users, "rb").read()
    text = raises(gs.GeodesicShapesError, gs.geodesic_distance, (plane_v, plane_f), 0,
                  solver="svg", cache_file=users)
    check(text is not None and users in text and "left untouched" in text, "cache_file on a user's file: %r" % text)
    check(open(users, "rb").read() == before, "cache_file overwrote a user's file")
    cache = os.path.join(folder, "plane.svgg")
    first = gs.geodesic_distance((plane_v, plane_f), 0, solver="svg", cache_file=cache)
    check(os.path.isfile(cache) and sorted(os.listdir(folder)) == ["my_mesh.ply", "plane.svgg"],
          "cache_file: %r" % sorted(os.listdir(folder)))
check(messages.GetOutput() == "", "messages reached the output window: %r" % messages.GetOutput()[:300])

gs_test.finish()
