"""Prints a SHA-256 of every output array of the five filters over a fixed set of parameters on
the bundled meshes (through the numpy functions, which call the filters): one line per result.
A change that must keep results bit for bit (a refactor) keeps every line; record the lines
before it and diff them after:

    PYTHONPATH=build/lib/python3/dist-packages python3 scripts/filter_output_hashes.py > before.txt
"""
import hashlib
import os
import sys
import warnings

import numpy

import geodesicshapes as gs
from geodesicshapes.mesh import points_of, triangles_of
from paraview.vtk.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOPLY import vtkPLYReader

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
data = os.path.join(root, "Data")


def digest(*arrays):
    """A short SHA-256 of the arrays' types, shapes and bytes (None counts as a value)."""
    h = hashlib.sha256()
    for a in arrays:
        if a is None:
            h.update(b"none")
            continue
        a = numpy.ascontiguousarray(a)
        h.update(str((a.dtype.str, a.shape)).encode())
        h.update(a.tobytes())
    return h.hexdigest()[:16]


def polydata_digest(polydata):
    """Points, cells and every point, cell and field array of a vtkPolyData but its timings."""
    parts = []
    if polydata.GetNumberOfPoints():
        parts.append(vtk_to_numpy(polydata.GetPoints().GetData()))
    for cells in (polydata.GetVerts(), polydata.GetLines(), polydata.GetPolys()):
        parts.append(vtk_to_numpy(cells.GetData()) if cells.GetNumberOfCells() else None)
    for attributes in (polydata.GetPointData(), polydata.GetCellData(), polydata.GetFieldData()):
        for i in range(attributes.GetNumberOfArrays()):
            array = attributes.GetAbstractArray(i)
            # (Wall times are not results.)
            if array.GetName().endswith("Seconds") or array.IsA("vtkStringArray"):
                continue
            parts.append(numpy.frombuffer(array.GetName().encode(), dtype=numpy.uint8))
            parts.append(vtk_to_numpy(array))
    return digest(*parts)


def report(name, value):
    """One output line: what was computed and its digest."""
    print("%-58s %s" % (name, value))
    sys.stdout.flush()


def mesh(name):
    """(vertices, triangles) of a bundled PLY mesh."""
    reader = vtkPLYReader()
    reader.SetFileName(os.path.join(data, name))
    reader.Update()
    return points_of(reader.GetOutput()), triangles_of(reader.GetOutput())


# (The filters' warnings, expected for some of these parameters, are not results.)
warnings.simplefilter("ignore")
meshes = {name: mesh(name + ".ply") for name in ("bumpy_sphere", "torus", "lshape", "cylinder")}

# SVG Geodesic Distance: every solver, vertex and point sources, a curve, a maximum distance.
for name, (vertices, triangles) in meshes.items():
    extent = vertices.max(axis=0) - vertices.min(axis=0)
    point = vertices[len(vertices) // 3] + 0.01 * extent
    curve = numpy.array([vertices[0], vertices[len(vertices) // 2]]) * 0.5 + \
        numpy.array([vertices[len(vertices) // 5], vertices[len(vertices) // 4]]) * 0.5
    for solver in ("virtual sources", "svg", "svg-dijkstra", "dgg", "exact"):
        d = gs.geodesic_distance((vertices, triangles), [0, len(vertices) // 2], solver=solver)
        report("distance %s %s vertices" % (name, solver), digest(d))
        d = gs.geodesic_distance((vertices, triangles), point.reshape(1, 3), solver=solver,
                                 maximum_distance=0.3 * float(extent.max()))
        report("distance %s %s point bounded" % (name, solver), digest(d))
        d = gs.geodesic_distance((vertices, triangles), None, curves=[curve], solver=solver)
        report("distance %s %s curve" % (name, solver), digest(d))

# Geodesic Polar Coordinates: exact and graph charts, a point, a curve, both angle modes.
for name, (vertices, triangles) in meshes.items():
    extent = float((vertices.max(axis=0) - vertices.min(axis=0)).max())
    for solver, label in (("exact", "k=0"), ("svg", "k=50")):
        for mode in ("geodesic", "arc-length"):
            c = gs.polar_coordinates((vertices, triangles), 7, 0.4 * extent, solver=solver, k=50,
                                     angle_mode=mode)
            report("polar %s %s %s" % (name, label, mode), digest(c.rho, c.theta, c.decal))
    curve = vertices[[3, len(vertices) // 7, len(vertices) // 6]]
    c = gs.polar_coordinates((vertices, triangles), curve, 0.3 * extent)
    report("polar %s curve" % name, digest(c.offset, c.arc_length, c.decal))

# Cross Field: N = 1, 2, 4, with a stroke.
fields = {}
for name, (vertices, triangles) in meshes.items():
    for n in (1, 2, 4):
        f = gs.cross_field((vertices, triangles), symmetry=n)
        fields[(name, n)] = f
        report("cross field %s N=%d" % (name, n), polydata_digest(f.vtk))
    stroke = vertices[[5, len(vertices) // 9, len(vertices) // 8]]
    f = gs.cross_field((vertices, triangles), symmetry=1, strokes=[stroke])
    report("cross field %s stroke" % name, polydata_digest(f.vtk))

# MSDT Source: the bundled silhouettes, one class and four, and a polygon.
shapes = [os.path.join(data, "shapes", s) for s in ("star.png", "gull.png", "leaf.png", "fish.png")]
star = gs.safe_distance_tables(images=shapes[:1], angle_bins=32, distance_steps=32)
four = gs.safe_distance_tables(images=shapes, angle_bins=32, distance_steps=32)
long_polygon = numpy.array([[0, 0], [6, 0], [6, 1], [0, 1]], dtype=float)
banana = gs.safe_distance_tables(polygons=[long_polygon], angle_bins=32, distance_steps=32)
for label, tables in (("star", star), ("four", four), ("long polygon", banana)):
    report("msdt %s tables" % label, digest(tables.values, tables.class_radius, tables.class_parts))
    report("msdt %s outlines" % label, polydata_digest(tables.outlines))

# Shape Distributor: modes, density, brush, long shapes, graph and exact charts, edits.
for name in ("bumpy_sphere", "torus", "lshape"):
    vertices, triangles = meshes[name]
    extent = float((vertices.max(axis=0) - vertices.min(axis=0)).max())
    field = fields[(name, 1)]
    density = 0.5 + 0.5 * (vertices[:, 0] - vertices[:, 0].min()) / (numpy.ptp(vertices[:, 0]) or 1)
    runs = {
        "random": dict(tables=star, mode="random"),
        "greedy": dict(tables=star, mode="greedy"),
        "circumcircle": dict(tables=star, mode="circumcircle"),
        "four density": dict(tables=four, mode="random", density=density),
        "long": dict(tables=banana, mode="random"),
        "exact charts": dict(tables=star, mode="random", solver="exact"),
        "brush": dict(tables=star, mode="random",
                      brush=(vertices[11], 0.3 * extent, 0.3)),
        "keep inside": dict(tables=four, mode="greedy", keep_inside=True),
    }
    for label, options in runs.items():
        r = gs.distribute_shapes(field.vtk, size=0.06 * extent, seed=5, **options)
        report("distribute %s %s (%d)" % (name, label, len(r)),
               digest(numpy.frombuffer(b"".join(bytes.fromhex(polydata_digest(p))
                                                for p in (r.placements, r.decals, r.outlines)),
                                       dtype=numpy.uint8)))
