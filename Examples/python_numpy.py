"""GeodesicShapes from plain Python with numpy: a mesh as arrays, every function, one picture.

Run with Debian's python3 (python3-paraview gives the VTK modules), the package on the path:
    PYTHONPATH=build/lib/python3/dist-packages xvfb-run -a python3 Examples/python_numpy.py
        [--output output] [--check]
Writes <output>/python_numpy.png: stars and bananas distributed on a torus made with numpy, following
a vector field, shrunk near a point by a geodesic-distance density, drawn as outlines over the
distance.
"""
import argparse
import math
import os
import sys

import numpy

import geodesicshapes as gs

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--output", default=os.path.join(root, "output"))
parser.add_argument("--check", action="store_true", help="exit with an error if a result is off")
args = parser.parse_args()
os.makedirs(args.output, exist_ok=True)

# 1. A mesh as numpy arrays: a torus (radii 1 and 0.4), 120 x 48 quads split in triangles.
nu, nv, R, r = 120, 48, 1.0, 0.4
u, v = numpy.meshgrid(numpy.arange(nu) * 2 * math.pi / nu, numpy.arange(nv) * 2 * math.pi / nv, indexing="ij")
vertices = numpy.column_stack([((R + r * numpy.cos(v)) * numpy.cos(u)).ravel(),
                               ((R + r * numpy.cos(v)) * numpy.sin(u)).ravel(),
                               (r * numpy.sin(v)).ravel()])
i, j = numpy.meshgrid(numpy.arange(nu), numpy.arange(nv), indexing="ij")
a, b = (i * nv + j).ravel(), (((i + 1) % nu) * nv + j).ravel()
c, d = (((i + 1) % nu) * nv + (j + 1) % nv).ravel(), (i * nv + (j + 1) % nv).ravel()
triangles = numpy.concatenate([numpy.column_stack([a, b, c]), numpy.column_stack([a, c, d])])
mesh = (vertices, triangles)
print("torus: %d vertices, %d triangles" % (len(vertices), len(triangles)))

# 2. Geodesic distance from the outer equator point at angle 0 (vertex 0).
distance = gs.geodesic_distance(mesh, 0)
print("geodesic distance: max %.3f" % numpy.nanmax(distance))

# 3. Geodesic polar coordinates around the same point (a decal's texture coordinates).
polar = gs.polar_coordinates(mesh, 0, radius=0.5, reference_direction=(0, 1, 0))
inside = ~numpy.isnan(polar.rho)
print("polar coordinates: %d vertices within 0.5" % inside.sum())

# 4. A vector field (N = 1): the torus has Euler characteristic 0, so no singularity is needed.
field = gs.cross_field(mesh, symmetry=1)
print("direction field: singularity indices sum to %.3f" % field.singularity_index.sum())

# 5. Safe distance tables of two shapes drawn with numpy (in one unit: polygons keep their
#    sizes relative to each other): a five-point star and a long banana (an arc of a ring), which
#    MSDT Source splits into parts that bend along the field.
angles = numpy.arange(10) * math.pi / 5 + math.pi / 2
radii = numpy.where(numpy.arange(10) % 2 == 0, 1.0, 0.4)
star = numpy.column_stack([radii * numpy.cos(angles), radii * numpy.sin(angles)])
arc = numpy.linspace(-0.6, 0.6, 40)
banana = numpy.concatenate([numpy.column_stack([2.2 * numpy.sin(arc), 2.2 * numpy.cos(arc) - 2.2]),
                            numpy.column_stack([1.8 * numpy.sin(arc[::-1]), 1.8 * numpy.cos(arc[::-1]) - 2.2])])
tables = gs.safe_distance_tables(polygons=[star, banana])
print("tables: classes of %s parts (radii %s), %d tables of %d x %d"
      % (list(tables.class_parts), numpy.round(tables.class_radius, 3), tables.values.shape[0],
         tables.values.shape[1], tables.values.shape[2]))

# A check of the distance against the exact solver (the default engine is virtual sources: no
# precomputation; solver="svg" is the near-exact saddle vertex graph).
exact = gs.geodesic_distance(mesh, 0, solver="exact")
relative = numpy.abs(distance - exact)[1:] / exact[1:]
print("virtual sources against exact: mean relative difference %.1e, largest %.1e"
      % (numpy.nanmean(relative), numpy.nanmax(relative)))

# 6. Distribution: smaller shapes near the source (density from the distance).
density = numpy.clip(distance / 1.5, 0.6, 1.0)
shapes = gs.distribute_shapes(field.vtk, tables, size=0.1, density=density, mode="greedy", seed=4,
                              verify_overlaps=True)
counts = numpy.bincount(shapes.class_ids.astype(int), minlength=2)
print("distribution: %d shapes (stars %d, bananas %d), %d overlapping pairs by the drawn outlines"
      % (len(shapes), counts[0], counts[1], shapes.overlapping_pairs))

# 7. A picture with VTK: the distance on the surface, the outlines over it.
from vtkmodules.util.numpy_support import numpy_to_vtk  # noqa: E402
import vtkmodules.vtkRenderingOpenGL2  # noqa: E402,F401
from vtkmodules.vtkIOImage import vtkPNGWriter  # noqa: E402
from vtkmodules.vtkRenderingCore import (  # noqa: E402
    vtkActor, vtkPolyDataMapper, vtkRenderWindow, vtkRenderer, vtkWindowToImageFilter)

surface = gs.as_polydata(mesh)
scalars = numpy_to_vtk(numpy.nan_to_num(distance), deep=True)
scalars.SetName("GeodesicDistance")
surface.GetPointData().SetScalars(scalars)
surface_mapper = vtkPolyDataMapper()
surface_mapper.SetInputData(surface)
surface_mapper.SetScalarRange(0.0, float(numpy.nanmax(distance)))
lut = surface_mapper.GetLookupTable()
lut.SetHueRange(0.6, 0.55)
lut.SetSaturationRange(0.25, 0.5)
lut.SetValueRange(0.95, 0.6)
lut.Build()
surface_actor = vtkActor()
surface_actor.SetMapper(surface_mapper)
outline_mapper = vtkPolyDataMapper()
outline_mapper.SetInputData(shapes.outlines)
outline_mapper.SetScalarModeToUseCellFieldData()
outline_mapper.SelectColorArray("ClassId")
outline_mapper.SetScalarRange(0, 1)
outline_lut = outline_mapper.GetLookupTable()
outline_lut.SetHueRange(0.0, 0.1)
outline_lut.SetSaturationRange(0.9, 0.9)
outline_lut.SetValueRange(0.6, 0.85)
outline_lut.Build()
outline_actor = vtkActor()
outline_actor.SetMapper(outline_mapper)
outline_actor.GetProperty().SetLineWidth(2.0)
renderer = vtkRenderer()
renderer.SetBackground(1.0, 1.0, 1.0)
renderer.AddActor(surface_actor)
renderer.AddActor(outline_actor)
camera = renderer.GetActiveCamera()
camera.SetPosition(2.2, -2.4, 2.2)
camera.SetFocalPoint(0.0, 0.0, -0.1)
camera.SetViewUp(0.0, 0.0, 1.0)
renderer.ResetCamera()
camera.Zoom(1.3)
window = vtkRenderWindow()
window.SetOffScreenRendering(1)
window.SetSize(900, 700)
window.AddRenderer(renderer)
window.Render()
grab = vtkWindowToImageFilter()
grab.SetInput(window)
writer = vtkPNGWriter()
picture = os.path.join(args.output, "python_numpy.png")
writer.SetFileName(picture)
writer.SetInputConnection(grab.GetOutputPort())
writer.Write()
print("picture: %s" % picture)

if args.check:
    problems = []
    # (Measured on this torus: mean 3.2e-3, largest 2.8e-2; a regular grid of diagonals all one
    # way is the hardest mesh measured for virtual sources.)
    if not (numpy.nanmean(relative) < 5e-3 and numpy.nanmax(relative) < 5e-2):
        problems.append("distance")
    if abs(field.singularity_index.sum()) > 1e-9:
        problems.append("field")
    if min(counts) == 0 or shapes.overlapping_pairs != 0:
        problems.append("distribution")
    if not os.path.getsize(picture):
        problems.append("picture")
    if problems:
        sys.exit("python_numpy check failed: %s" % problems)
    print("check passed")
