"""Meshes as numpy arrays and as vtkPolyData."""
import numpy
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkDataObject, vtkPolyData


def as_polydata(mesh):
    """A vtkPolyData for ``mesh``: a vtkPolyData (returned as is) or a ``(vertices, triangles)``
    pair: vertices an (n, 3) array of coordinates, triangles an (m, 3) array of vertex indices
    (0-based). Raises TypeError or ValueError for anything else."""
    if isinstance(mesh, vtkPolyData):
        return mesh
    if isinstance(mesh, vtkDataObject):
        raise TypeError("mesh: a %s is not a surface; give a vtkPolyData or (vertices, triangles)"
                        % mesh.GetClassName())
    try:
        vertices, triangles = mesh
    except (TypeError, ValueError):
        raise TypeError("mesh: give a vtkPolyData or a (vertices, triangles) pair of arrays")
    vertices = numpy.ascontiguousarray(vertices, dtype=numpy.float64)
    triangles = numpy.asarray(triangles)
    if vertices.ndim != 2 or vertices.shape[1] != 3:
        raise ValueError("mesh: vertices must be an (n, 3) array, not %s" % (vertices.shape,))
    if triangles.ndim != 2 or triangles.shape[1] != 3:
        raise ValueError("mesh: triangles must be an (m, 3) array, not %s" % (triangles.shape,))
    if not numpy.issubdtype(triangles.dtype, numpy.integer):
        raise ValueError("mesh: triangles must hold integer vertex indices")
    if triangles.size and (triangles.min() < 0 or triangles.max() >= len(vertices)):
        raise ValueError("mesh: a triangle refers to a vertex index outside 0..%d" % (len(vertices) - 1))
    points = vtkPoints()
    points.SetData(numpy_to_vtk(vertices, deep=True))
    m = len(triangles)
    offsets = numpy_to_vtkIdTypeArray(numpy.arange(0, 3 * m + 1, 3, dtype=numpy.int64), deep=True)
    connectivity = numpy_to_vtkIdTypeArray(triangles.astype(numpy.int64).ravel(), deep=True)
    cells = vtkCellArray()
    cells.SetData(offsets, connectivity)
    polydata = vtkPolyData()
    polydata.SetPoints(points)
    polydata.SetPolys(cells)
    return polydata


def points_of(polydata):
    """The (n, 3) point coordinates of a vtkPolyData (a copy)."""
    if polydata.GetPoints() is None:
        return numpy.zeros((0, 3))
    return numpy.array(vtk_to_numpy(polydata.GetPoints().GetData()), dtype=numpy.float64)


def triangles_of(polydata):
    """The (m, 3) vertex indices of a vtkPolyData's triangles (its polygons with 3 points)."""
    polys = polydata.GetPolys()
    if polys is None or polys.GetNumberOfCells() == 0:
        return numpy.zeros((0, 3), dtype=numpy.int64)
    offsets = vtk_to_numpy(polys.GetOffsetsArray())
    connectivity = vtk_to_numpy(polys.GetConnectivityArray())
    sizes = numpy.diff(offsets)
    if numpy.all(sizes == 3):
        return connectivity.reshape(-1, 3).astype(numpy.int64)
    return numpy.array([connectivity[offsets[k]:offsets[k] + 3] for k in range(len(sizes)) if sizes[k] == 3],
                       dtype=numpy.int64).reshape(-1, 3)


def point_cloud(points, lines=()):
    """A vtkPolyData of points (an (n, 3) array) and optional polylines (each an (k, 3) array,
    appended after the points)."""
    points = numpy.asarray(points, dtype=numpy.float64).reshape(-1, 3)
    all_points = [points] + [numpy.asarray(line, dtype=numpy.float64).reshape(-1, 3) for line in lines]
    coordinates = numpy.concatenate(all_points) if all_points else numpy.zeros((0, 3))
    vtk_points = vtkPoints()
    vtk_points.SetData(numpy_to_vtk(numpy.ascontiguousarray(coordinates), deep=True))
    polydata = vtkPolyData()
    polydata.SetPoints(vtk_points)
    start = len(points)
    if lines:
        cells = vtkCellArray()
        for line in all_points[1:]:
            cells.InsertNextCell(len(line))
            for k in range(len(line)):
                cells.InsertCellPoint(start + k)
            start += len(line)
        polydata.SetLines(cells)
    return polydata
