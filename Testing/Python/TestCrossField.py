"""pvpython test: load the GeodesicShapes plugin and run CrossField as a user would.

- Smoothest fields (N = 1, 2, 4) on the bundled sphere, torus and cylinder (with boundary):
  SingularityIndexSum and the sum of the SingularityIndex point array equal the Euler
  characteristic (Poincare-Hopf); unit cell directions tangent to the faces.
- Prescribed singularities through a Singularities input built in Python (two +1 at the poles of
  the sphere): exactly there, nowhere else; a wrong sum is an error with an empty output.
- A stroke (Line source) across the planar grid: the cross field follows it within 1 degree in
  every crossed triangle and, the grid being flat, everywhere.
- Missing Index array: error, empty output. Render.

Usage: pvpython TestCrossField.py --plugin <GeodesicShapes.so> --data <Data dir>
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
check("CrossField" in globals(), "the plugin does not define CrossField")


def reader(name):
    return PLYReader(FileNames=[os.path.join(args.data, name)])


def arrays(proxy):
    out = servermanager.Fetch(proxy)
    res = {"cells": out.GetNumberOfCells(), "output": out}
    if out.GetNumberOfCells() == 0:
        return res
    res["cell_dir"] = vtk_to_numpy(out.GetCellData().GetArray("Direction")).astype(float)
    res["point_dir"] = vtk_to_numpy(out.GetPointData().GetArray("Direction")).astype(float)
    res["index"] = vtk_to_numpy(out.GetPointData().GetArray("SingularityIndex")).astype(float)
    res["chi"] = out.GetFieldData().GetArray("EulerCharacteristic").GetValue(0)
    res["sum"] = out.GetFieldData().GetArray("SingularityIndexSum").GetValue(0)
    res["points"] = vtk_to_numpy(out.GetPoints().GetData()).astype(float)
    polys = vtk_to_numpy(out.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    res["tris"] = polys
    return res


def face_normals(r):
    p = r["points"][r["tris"]]
    n = numpy.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    return n / numpy.linalg.norm(n, axis=1)[:, None]


expected_chi = {"sphere.ply": 2, "torus.ply": 0, "cylinder.ply": 0}
for name, chi in expected_chi.items():
    mesh = reader(name)
    for n in (1, 2, 4):
        field = CrossField(Input=mesh, Symmetry=n)
        r = arrays(field)
        check(r["cells"] > 0, "%s N=%d: empty output" % (name, n))
        if r["cells"] == 0:
            continue
        check(r["chi"] == chi, "%s: Euler characteristic %s, expected %d" % (name, r["chi"], chi))
        check(abs(r["sum"] - chi) < 1e-9, "%s N=%d: SingularityIndexSum %g" % (name, n, r["sum"]))
        boundary_free = name != "cylinder.ply"
        if boundary_free:
            check(abs(r["index"].sum() - chi) < 1e-9,
                  "%s N=%d: point indices sum to %g" % (name, n, r["index"].sum()))
        q = numpy.round(r["index"] * n)
        check(numpy.allclose(q, r["index"] * n), "%s N=%d: indices not multiples of 1/N" % (name, n))
        d = r["cell_dir"]
        check(numpy.allclose(numpy.linalg.norm(d, axis=1), 1.0, atol=1e-9),
              "%s N=%d: cell directions are not unit vectors" % (name, n))
        check(numpy.abs((d * face_normals(r)).sum(axis=1)).max() < 1e-9,
              "%s N=%d: cell directions are not tangent" % (name, n))
        print("%s N=%d: %d singular vertices, index sum %g" % (name, n, (r["index"] != 0).sum(), r["sum"]))
        Delete(field)

# Prescribed singularities: +1 at both poles of the sphere (points given in space).
sphere = reader("sphere.ply")
sphere_points = arrays(CrossField(Input=sphere, Symmetry=1))["points"]
north = int(numpy.argmax(sphere_points[:, 2]))
south = int(numpy.argmin(sphere_points[:, 2]))
poles = ProgrammableSource(OutputDataSetType="vtkPolyData")
poles.Script = """
import vtk
pts = vtk.vtkPoints()
pts.InsertNextPoint(%r)
pts.InsertNextPoint(%r)
idx = vtk.vtkDoubleArray()
idx.SetName("Index")
idx.InsertNextValue(1.0)
idx.InsertNextValue(%s)
out = self.GetPolyDataOutput()
out.SetPoints(pts)
out.GetPointData().AddArray(idx)
""" % (tuple(sphere_points[north] * 1.01), tuple(sphere_points[south] * 1.01), "1.0")
prescribed = CrossField(Input=sphere, Singularities=poles, Symmetry=1,
                        Mode="Prescribed singularities")
r = arrays(prescribed)
check(r["cells"] > 0, "prescribed: empty output")
if r["cells"] > 0:
    expected = numpy.zeros(len(r["index"]))
    expected[north] = expected[south] = 1.0
    check(numpy.array_equal(r["index"], expected),
          "prescribed: singularities at %s" % numpy.nonzero(r["index"])[0])

# Wrong sum: an error and an empty output.
poles.Script = poles.Script.replace("idx.InsertNextValue(1.0)\nout", "idx.InsertNextValue(0.0)\nout")
r = arrays(prescribed)
check(r["cells"] == 0, "wrong index sum: the output is not empty")

# A missing Index array: an error and an empty output.
no_index = ProgrammableSource(OutputDataSetType="vtkPolyData")
no_index.Script = """
import vtk
pts = vtk.vtkPoints()
pts.InsertNextPoint(0, 0, 1)
self.GetPolyDataOutput().SetPoints(pts)
"""
r = arrays(CrossField(Input=sphere, Singularities=no_index, Symmetry=1,
                      Mode="Prescribed singularities"))
check(r["cells"] == 0, "missing Index array: the output is not empty")

# A stroke across the planar grid (the unit square).
grid = reader("planar_grid.ply")
stroke = Line(Point1=[0.2, 0.3, 0.0], Point2=[0.8, 0.6, 0.0], Resolution=4)
s = numpy.array([0.6, 0.3, 0.0]) / math.hypot(0.6, 0.3)
for n in (1, 4):
    for mode in ("Smoothest", "Prescribed singularities"):
        if mode != "Smoothest" and n == 1:
            continue  # a vector field on a square without boundary indices: sum 1 needed
        f = CrossField(Input=grid, Strokes=stroke, Symmetry=n, Mode=mode)
        if mode != "Smoothest":
            corners = ProgrammableSource(OutputDataSetType="vtkPolyData")
            corners.Script = """
import vtk
pts = vtk.vtkPoints()
idx = vtk.vtkDoubleArray()
idx.SetName("Index")
for p in ((0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)):
    pts.InsertNextPoint(p)
    idx.InsertNextValue(0.25)
out = self.GetPolyDataOutput()
out.SetPoints(pts)
out.GetPointData().AddArray(idx)
"""
            f.Singularities = corners
        r = arrays(f)
        check(r["cells"] > 0, "stroke %s N=%d: empty output" % (mode, n))
        if r["cells"] == 0:
            continue
        d = r["cell_dir"]
        angle = numpy.arctan2(d[:, 1], d[:, 0]) - math.atan2(s[1], s[0])
        period = 2 * math.pi / n
        dev = numpy.abs((angle + period / 2) % period - period / 2)
        if mode == "Smoothest":
            check(dev.max() < math.radians(1.0),
                  "stroke %s N=%d: largest deviation %g degrees" % (mode, n, math.degrees(dev.max())))
        else:
            # Boundary-aligned cross field (corners 1/4) with the stroke: the crossed faces follow
            # the stroke.
            pts = r["points"][r["tris"]].mean(axis=1)
            t = numpy.clip(((pts - [0.2, 0.3, 0]) @ s) / math.hypot(0.6, 0.3), 0, 1)
            near = numpy.linalg.norm(pts - ([0.2, 0.3, 0] + numpy.outer(t, [0.6, 0.3, 0])), axis=1)
            crossed = near < 0.02
            check(crossed.sum() > 5 and dev[crossed].max() < math.radians(1.0),
                  "stroke %s N=%d: deviation on the stroke %g degrees" % (mode, n, math.degrees(dev[crossed].max())))
        print("stroke %s N=%d: largest deviation %.2e degrees" % (mode, n, math.degrees(dev.max())))

view = CreateRenderView()
field = CrossField(Input=reader("torus.ply"))
display = Show(field, view)
ColorBy(display, ("POINTS", "SingularityIndex"))
Render(view)
Delete(view)
del view

gs_test.finish("all checks passed")
