"""GeodesicShapes for Python.

Two layers, both usable from plain ``python3`` (with ParaView's VTK Python modules, Debian's
``python3-paraview``) and from ``pvpython``:

* the five filters as VTK classes, for VTK pipelines::

      from geodesicshapes import vtkSVGGeodesicDistance
      f = vtkSVGGeodesicDistance()
      f.SetInputConnection(reader.GetOutputPort())
      f.AddSourceVertexId(0)
      f.Update()

* numpy functions around them (``geodesic_distance``, ``polar_coordinates``, ``cross_field``,
  ``safe_distance_tables``, ``distribute_shapes``), where a mesh is a vtkPolyData or a
  ``(vertices, triangles)`` pair of arrays, results are numpy arrays, and a filter's error is a
  ``GeodesicShapesError`` carrying its message.
"""
# The wrapped module's VTK dependencies first (their Python types must exist).
from vtkmodules import vtkCommonCore as _vtkCommonCore  # noqa: F401
from vtkmodules import vtkCommonDataModel as _vtkCommonDataModel  # noqa: F401
from vtkmodules import vtkCommonExecutionModel as _vtkCommonExecutionModel  # noqa: F401

from .GeodesicShapesFilters import (  # noqa: F401
    vtkCrossField,
    vtkGeodesicPolarCoordinates,
    vtkMSDTSource,
    vtkSVGGeodesicDistance,
    vtkShapeDistributor,
)
from .mesh import as_polydata, points_of, triangles_of  # noqa: F401
from .functions import (  # noqa: F401
    CrossField,
    Distribution,
    GeodesicShapesAborted,
    GeodesicShapesError,
    PolarCoordinates,
    SafeDistanceTables,
    cross_field,
    distribute_shapes,
    geodesic_distance,
    polar_coordinates,
    safe_distance_tables,
)

__all__ = [
    "vtkSVGGeodesicDistance", "vtkGeodesicPolarCoordinates", "vtkMSDTSource", "vtkCrossField",
    "vtkShapeDistributor", "as_polydata", "points_of", "triangles_of", "GeodesicShapesError",
    "GeodesicShapesAborted",
    "geodesic_distance", "polar_coordinates", "cross_field", "safe_distance_tables",
    "distribute_shapes", "PolarCoordinates", "CrossField", "SafeDistanceTables", "Distribution",
]
