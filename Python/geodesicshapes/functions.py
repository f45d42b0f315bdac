"""numpy functions around the GeodesicShapes filters.

A mesh is a vtkPolyData or a ``(vertices, triangles)`` pair of numpy arrays (see
``geodesicshapes.as_polydata``); results are numpy arrays, with the filters' VTK outputs kept on
the result objects (attribute ``vtk``) where they carry more. A filter's error (bad input, bad
parameter) raises ``GeodesicShapesError`` with the filter's own message; its warnings become
Python warnings (category ``GeodesicShapesWarning``).

Every function takes ``progress=None``: a callable given the fraction done (0 to 1) as the
filter advances through its phases (graph, candidates, rounds, decals, ...), on the calling
thread, at most about every 0.1 s and once at 1; when it returns False the work stops soon after
and ``GeodesicShapesAborted`` is raised. E.g. ``progress=lambda f: print("%3d%%" % (100 * f))``.
"""
import warnings

import math
import numpy
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import VTK_STRING, vtkCommand
from vtkmodules.vtkCommonDataModel import vtkDataObject, vtkImageData, vtkPolyData

from .GeodesicShapesFilters import (
    vtkCrossField,
    vtkGeodesicPolarCoordinates,
    vtkMSDTSource,
    vtkSVGGeodesicDistance,
    vtkShapeDistributor,
)
from .mesh import as_polydata, point_cloud


class GeodesicShapesError(RuntimeError):
    """A filter refused its input or parameters; the message is the filter's."""


class GeodesicShapesAborted(GeodesicShapesError):
    """The caller's progress callback returned False: the work stopped, no result."""


class GeodesicShapesWarning(UserWarning):
    """A filter's warning (the result is valid)."""


def _message(text):
    # "ERROR: In file, line N\nvtkClass (0x...): message" -> "message"
    text = str(text).strip()
    if "): " in text:
        text = text.split("): ", 1)[1]
    return " ".join(text.split())


def _update(algorithm, what, progress=None):
    """Updates ``algorithm``; its errors raise GeodesicShapesError, its warnings are warned;
    ``progress(fraction)`` is called as it advances, and returning False aborts it."""
    if progress is not None and not callable(progress):
        raise TypeError("%s: progress must be a callable taking the fraction done, not %r"
                        % (what, progress))
    errors, warned = [], []
    stopped = []

    def on_progress(caller, event):
        if not stopped and progress(caller.GetProgress()) is False:
            stopped.append(True)
            caller.SetAbortExecute(1)

    @calldata_type(VTK_STRING)
    def on_error(caller, event, text):
        errors.append(_message(text))

    @calldata_type(VTK_STRING)
    def on_warning(caller, event, text):
        warned.append(_message(text))

    tags = [algorithm.AddObserver(vtkCommand.ErrorEvent, on_error),
            algorithm.AddObserver(vtkCommand.WarningEvent, on_warning)]
    if progress is not None:
        tags.append(algorithm.AddObserver(vtkCommand.ProgressEvent, on_progress))
    try:
        algorithm.Update()
    finally:
        for tag in tags:
            algorithm.RemoveObserver(tag)
    if stopped:  # (each call makes its own filter: nothing of the aborted run is kept)
        raise GeodesicShapesAborted("%s: aborted by the progress callback" % what)
    for text in warned:
        warnings.warn("%s: %s" % (what, text), GeodesicShapesWarning, stacklevel=3)
    if errors:
        raise GeodesicShapesError("%s: %s" % (what, errors[0]))


def _point_array(data, name):
    array = data.GetPointData().GetArray(name)
    return None if array is None else numpy.array(vtk_to_numpy(array))


def _cell_array(data, name):
    array = data.GetCellData().GetArray(name)
    return None if array is None else numpy.array(vtk_to_numpy(array))


def _field_value(data, name, default=None):
    array = data.GetFieldData().GetAbstractArray(name)
    if array is None or array.GetNumberOfTuples() == 0:
        return default
    return array.GetValue(0) if not hasattr(array, "GetComponent") else array.GetComponent(0, 0)


def _copy(polydata):
    out = vtkPolyData()
    out.ShallowCopy(polydata)
    return out


# The geodesic engines, one vocabulary for every function (the filters' Solver property):
# solver, k (graph solvers) and graph_accuracy ("dgg").
_SOLVERS = {"svg": vtkSVGGeodesicDistance.SVG_LABEL_CORRECTING,
            "svg-dijkstra": vtkSVGGeodesicDistance.SVG_DIJKSTRA,
            "dgg": vtkSVGGeodesicDistance.DGG,
            "exact": vtkSVGGeodesicDistance.EXACT,
            "virtual sources": vtkSVGGeodesicDistance.VIRTUAL_SOURCES}
# The engines with departure angles (polar coordinates and the distributor's charts).
_CHART_SOLVERS = ("exact", "svg", "dgg")


def _set_engine(f, solver, allowed, k, graph_accuracy):
    if solver not in allowed:
        raise ValueError("solver must be one of %s, not %r" % (sorted(allowed), solver))
    f.SetSolver(_SOLVERS[solver])
    f.SetK(int(k))
    f.SetGraphAccuracy(float(graph_accuracy))


def geodesic_distance(mesh, sources=None, curves=(), solver="virtual sources", k=50, graph_accuracy=1e-3,
                      maximum_distance=0.0, cache_file=None, return_vtk=False,
                      reached_stencil=False, progress=None):
    """Geodesic distance (shortest path on the surface) from sources to every vertex.

    mesh: a vtkPolyData or (vertices, triangles).
    sources: a vertex index, a sequence of vertex indices, or an (s, 3) array of points (each
        snapped to the closest surface point, a vertex, an edge or a triangle point).
    curves: polylines on or near the surface, each a (k, 3) array: the distance to the curve.
    solver: "virtual sources" (default: no precomputation, the soonest first answer; exact on
        flat meshes, a mean relative error of 1e-3 to 1.9e-3 on most real meshes measured, but
        6e-3 to 1e-2 on regular-grid tori and CAD parts with sharp creases, where "dgg" is the
        better choice; straight curves on flat parts exact), "svg" (saddle vertex graph, label-correcting: near-exact, fast once the graph
        is built), "svg-dijkstra", "dgg" (discrete geodesic graph: largest relative error
        within `graph_accuracy`), or "exact" (exact polyhedral geodesics).
    k: the graph's neighbourhood size (graph solvers; default 50). graph_accuracy: the DGG's
        largest relative error, 1e-5 .. 0.1 (default 1e-3). maximum_distance: stop there
        (0: none; beyond it NaN). cache_file: where the graph is saved and read back.
    reached_stencil: "dgg" only: refine over the vertices the graph's construction reached,
        not only its links (the filter's ReachedStencil: a 2-3x smaller mean error at
        graph_accuracy 0.1 for twice the graph's memory).
    Returns an (n,) array of distances (NaN where unreachable), and the filter's output too
    when return_vtk is true.
    """
    f = vtkSVGGeodesicDistance()
    f.SetInputData(as_polydata(mesh))
    _set_engine(f, solver, _SOLVERS, k, graph_accuracy)
    f.SetReachedStencil(bool(reached_stencil))
    f.SetMaximumDistance(float(maximum_distance))
    if cache_file:
        f.SetCacheFileName(str(cache_file))
    points = None
    if sources is not None:
        array = numpy.asarray(sources)
        if array.ndim <= 1 and numpy.issubdtype(array.dtype, numpy.integer):
            for v in numpy.atleast_1d(array):
                f.AddSourceVertexId(int(v))
        elif array.ndim == 2 and array.shape[1] == 3:
            points = array.astype(numpy.float64)
        else:
            raise ValueError("sources: a vertex index, a list of them, or an (s, 3) array of points")
    if points is not None or len(curves):
        f.SetSourcesData(point_cloud(points if points is not None else numpy.zeros((0, 3)), list(curves)))
    elif sources is None:
        raise ValueError("geodesic_distance: give sources (vertex indices or points) or curves")
    _update(f, "geodesic_distance", progress)
    out = f.GetOutput()
    distance = _point_array(out, "GeodesicDistance")
    return (distance, out) if return_vtk else distance


class PolarCoordinates:
    """Geodesic polar coordinates about a point (rho, theta) or a curve (offset, arc_length).

    Attributes: rho and theta (point source: geodesic distance, and the polar angle in [0, 2 pi)
    from the reference direction), or offset and arc_length (curve source: signed geodesic
    distance to the curve, and the normalized arc length along the point's offset curve), decal
    ((n, 2) texture coordinates), all NaN beyond the radius; vtk: the filter's output."""

    def __init__(self, output, curve):
        self.vtk = output
        if curve:
            self.offset = _point_array(output, "Offset")
            self.arc_length = _point_array(output, "ArcLength")
            self.rho = self.theta = None
        else:
            self.rho = _point_array(output, "GeodesicDistance")
            self.theta = _point_array(output, "PolarAngle")
            self.offset = self.arc_length = None
        self.decal = _point_array(output, "DecalCoordinates")


def polar_coordinates(mesh, source, radius, reference_direction=None, solver="exact", k=50,
                      graph_accuracy=1e-3, decal_size=None, angle_mode="geodesic", progress=None):
    """Geodesic polar coordinates of the vertices within ``radius`` of a source.

    source: a vertex index, a point ((3,) array, snapped to the surface) or a curve ((k, 3)
        array with k >= 2: curve coordinates, offset and arc length).
    radius: how far (geodesic distance). reference_direction: the direction of angle 0 at the
        source (projected onto the surface; default the filter's). solver: "exact" (default:
        exact geodesics), "svg" (the saddle vertex graph of k) or "dgg" (the discrete geodesic
        graph of k and graph_accuracy), as geodesic_distance names them. decal_size: side of the square that the decal
        coordinates map to [0, 1]^2 (default 2 radius; with an infinite radius, twice the mesh's
        bounding box diagonal). angle_mode: "geodesic" (the direction of
        the geodesic at the source) or "arc-length" (proportional to arc length along each
        geodesic circle).
    Returns a PolarCoordinates.
    """
    f = vtkGeodesicPolarCoordinates()
    polydata = as_polydata(mesh)
    f.SetInputData(polydata)
    radius = float(radius)
    f.SetRadius(radius)
    _set_engine(f, solver, _CHART_SOLVERS, k, graph_accuracy)
    if decal_size is None:
        # Twice the radius (the decal's inscribed disc is the geodesic disc); a radius that is
        # not finite (the whole surface, or an error the filter names) leaves the decal the
        # whole mesh: twice its bounding box diagonal.
        decal_size = 2.0 * radius
        if not math.isfinite(decal_size):
            decal_size = 2.0 * (polydata.GetLength() or 1.0)
    f.SetDecalSize(float(decal_size))
    if reference_direction is not None:
        f.SetReferenceDirection(*[float(x) for x in reference_direction])
    if angle_mode == "geodesic":
        f.SetAngleModeToGeodesicDirection()
    elif angle_mode == "arc-length":
        f.SetAngleModeToIsoCurveArcLength()
    else:
        raise ValueError("angle_mode must be 'geodesic' or 'arc-length', not %r" % (angle_mode,))
    array = numpy.asarray(source)
    curve = False
    if array.ndim == 0 and numpy.issubdtype(array.dtype, numpy.integer):
        f.SetSourceVertexId(int(array))
    elif array.shape == (3,):
        f.SetSourceData(point_cloud(array.reshape(1, 3)))
    elif array.ndim == 2 and array.shape[1] == 3 and len(array) >= 2:
        f.SetSourceData(point_cloud(numpy.zeros((0, 3)), [array]))
        curve = True
    else:
        raise ValueError("source: a vertex index, a (3,) point or a (k, 3) curve")
    _update(f, "polar_coordinates", progress)
    return PolarCoordinates(f.GetOutput(), curve)


class CrossField:
    """A direction field: face_directions ((m, 3), unit tangent vectors, one per triangle),
    vertex_directions ((n, 3)), singularity_index ((n,), multiples of 1/N), symmetry (N),
    and vtk (the filter's output: the mesh with these arrays, ready for distribute_shapes)."""

    def __init__(self, output, symmetry):
        self.vtk = output
        self.face_directions = _cell_array(output, "Direction")
        self.vertex_directions = _point_array(output, "Direction")
        self.singularity_index = _point_array(output, "SingularityIndex")
        self.symmetry = symmetry


def cross_field(mesh, symmetry=4, singularities=None, strokes=(), curvature_alignment=None,
                progress=None):
    """The smoothest N-direction field on the mesh (trivial connections, Crane et al. 2010).

    symmetry: N = 1 (vectors, for birds or fish), 2 (lines) or 4 (crosses; default).
    singularities: None (placed automatically), or (points, indices): points an (s, 3) array
        (snapped to the nearest vertex), indices (s,) multiples of 1/N adding up to the Euler
        characteristic: exactly these singularities.
    strokes: polylines, each a (k, 3) array on or near the surface, that the field follows.
    curvature_alignment: > 0 aligns a 2- or 4-field with the principal curvature directions.
    Returns a CrossField.
    """
    f = vtkCrossField()
    f.SetInputData(as_polydata(mesh))
    f.SetSymmetry(int(symmetry))
    if curvature_alignment is not None:
        f.SetCurvatureAlignment(float(curvature_alignment))
    if singularities is not None:
        points, indices = singularities
        points = numpy.asarray(points, dtype=numpy.float64).reshape(-1, 3)
        indices = numpy.asarray(indices, dtype=numpy.float64).reshape(-1)
        if len(points) != len(indices):
            raise ValueError("singularities: as many indices as points")
        data = point_cloud(points)
        array = numpy_to_vtk(indices, deep=True)
        array.SetName("Index")
        data.GetPointData().AddArray(array)
        f.SetSingularitiesData(data)
        f.SetModeToPrescribedSingularities()
    if len(strokes):
        f.SetStrokesData(point_cloud(numpy.zeros((0, 3)), list(strokes)))
    _update(f, "cross_field", progress)
    return CrossField(f.GetOutput(), int(symmetry))


class SafeDistanceTables:
    """Minimum safe distance tables of 2D shapes (MSDT Source's outputs).

    Attributes: vtk (the tables image, what distribute_shapes takes), outlines (vtkPolyData of
    the class contours), silhouettes (vtkImageData, the decal textures), values ((P*P, ka, ka)
    safe centre distances in units of the first class's circumradius, P parts in all),
    class_radius ((classes,)), class_parts ((classes,) number of parts of each class)."""

    def __init__(self, source):
        self.vtk = vtkImageData()
        self.vtk.DeepCopy(source.GetOutputDataObject(0))
        self.outlines = vtkPolyData()
        self.outlines.DeepCopy(source.GetOutputDataObject(1))
        self.silhouettes = vtkImageData()
        self.silhouettes.DeepCopy(source.GetOutputDataObject(2))
        dims = self.vtk.GetDimensions()
        values = vtk_to_numpy(self.vtk.GetPointData().GetArray("SafeDistance"))
        self.values = numpy.array(values).reshape(dims[2], dims[1], dims[0])
        fd = self.vtk.GetFieldData()
        self.class_radius = numpy.array(vtk_to_numpy(fd.GetArray("ClassRadius")))
        self.class_parts = numpy.array(vtk_to_numpy(fd.GetArray("ClassNumberOfParts"))).astype(int)


def safe_distance_tables(images=(), polygons=(), angle_bins=64, distance_steps=64,
                         maximum_aspect_ratio=2.0, texture_size=256, progress=None):
    """Minimum safe distance tables of shapes given as images and/or polygons.

    images: file names of silhouettes (PNG with transparency, or dark shapes on a light
        background), one class each. polygons: classes after the images, each a (k, 2) ring or a
        list of rings (even-odd: holes allowed), in any unit. angle_bins, distance_steps: the
        tables' resolution (default 64 x 64). maximum_aspect_ratio: longer shapes are split into
        parts that bend along the field. texture_size: side of the silhouette textures.
    Returns a SafeDistanceTables.
    """
    f = vtkMSDTSource()
    if isinstance(images, str):
        images = [images]
    for name in images:
        f.AddShapeFileName(str(name))
    if len(polygons):
        rings, classes = [], []
        for c, shape in enumerate(polygons):
            shape_rings = [shape] if numpy.asarray(shape[0]).ndim == 1 else list(shape)
            for ring in shape_rings:
                ring = numpy.asarray(ring, dtype=numpy.float64)
                if ring.ndim != 2 or ring.shape[1] != 2 or len(ring) < 3:
                    raise ValueError("polygons: each ring is a (k, 2) array with k >= 3")
                if not numpy.array_equal(ring[0], ring[-1]):
                    ring = numpy.vstack([ring, ring[:1]])  # closed rings
                rings.append(numpy.column_stack([ring, numpy.zeros(len(ring))]))
                classes.append(c)
        data = point_cloud(numpy.zeros((0, 3)), rings)
        ids = numpy_to_vtk(numpy.asarray(classes, dtype=numpy.int32), deep=True)
        ids.SetName("ClassId")
        data.GetCellData().AddArray(ids)
        f.SetPolygonsData(data)
    f.SetAngleBins(int(angle_bins))
    f.SetDistanceSteps(int(distance_steps))
    f.SetMaximumAspectRatio(float(maximum_aspect_ratio))
    f.SetTextureSize(int(texture_size))
    _update(f, "safe_distance_tables", progress)
    return SafeDistanceTables(f)


class Distribution:
    """Placed shapes: positions ((s, 3), centres on the surface), directions ((s, 3)), normals,
    class_ids ((s,)), scales ((s,), density factors), face_ids ((s,), the triangle of each
    centre), shape_size (the size used); placements, decals and outlines: the filter's three
    vtkPolyData outputs; overlapping_pairs (when verify_overlaps was asked, else None)."""

    def __init__(self, f):
        self.placements = vtkPolyData()
        self.placements.DeepCopy(f.GetOutputDataObject(0))
        self.decals = vtkPolyData()
        self.decals.DeepCopy(f.GetOutputDataObject(1))
        self.outlines = vtkPolyData()
        self.outlines.DeepCopy(f.GetOutputDataObject(2))
        p = self.placements
        n = p.GetNumberOfPoints()
        self.positions = (numpy.array(vtk_to_numpy(p.GetPoints().GetData())) if n
                          else numpy.zeros((0, 3)))
        empty3 = numpy.zeros((0, 3))
        self.directions = _point_array(p, "Direction") if n else empty3
        self.normals = _point_array(p, "Normal") if n else empty3
        self.class_ids = _point_array(p, "ClassId") if n else numpy.zeros(0, dtype=int)
        self.scales = _point_array(p, "Scale") if n else numpy.zeros(0)
        self.face_ids = _point_array(p, "FaceId") if n else numpy.zeros(0, dtype=int)
        self.shape_size = _field_value(p, "ShapeSizeUsed")
        pairs = _field_value(p, "OverlappingPairs")
        self.overlapping_pairs = None if pairs is None else int(pairs)

    def __len__(self):
        return len(self.positions)


_MODES = {"random": vtkShapeDistributor.RANDOM, "greedy": vtkShapeDistributor.GREEDY,
          "circumcircle": vtkShapeDistributor.CIRCUMCIRCLE_POISSON_DISK}


def distribute_shapes(mesh, tables, size=None, directions=None, symmetry=None, density=None,
                      mode="random", seed=0, class_weights=None, maximum_shapes=0,
                      keep_inside=False, verify_overlaps=False, threads=0, solver="dgg", k=50,
                      graph_accuracy=0.1, brush=None, progress=None):
    """Places shapes on the surface without any two overlapping (Wang et al. 2016).

    mesh: a vtkPolyData (e.g. CrossField.vtk, whose cell array Direction is then used) or
        (vertices, triangles).
    tables: a SafeDistanceTables (or MSDT Source's tables image).
    size: circumradius of the first class at density 1, in mesh units (default: 4% of the
        mesh's largest bounding-box side).
    directions: the field the shapes turn to: an (m, 3) array (one vector per triangle) or an
        (n, 3) array (per vertex, averaged per triangle N-symmetrically); default: the mesh's
        cell array Direction if it has one, else the smoothest vector field (cross_field with
        symmetry 1).
    symmetry: N of the directions (1, 2 or 4; default: the mesh's field data, else 1).
    density: an (n,) array of per-vertex size factors f (f = 0.5: four times as many shapes per
        unit area; f <= 0 masks the triangles around). mode: "random" (dart throwing), "greedy"
        (denser) or "circumcircle" (the baseline). seed: the result depends on it only.
    class_weights: how often each class is proposed (the counts follow the weights until the
        surface fills; then smaller classes fill gaps and exceed their share). maximum_shapes:
        stop there (0: none).
    keep_inside: keep shapes off the mesh boundary. verify_overlaps: check the result by the
    drawn outlines (Distribution.overlapping_pairs). threads: 0 all. solver: the charts'
    engine, "dgg" (default: the discrete geodesic graph of k and graph_accuracy, default 0.1),
    "svg" (the saddle vertex graph of k) or "exact" (no graph), as geodesic_distance names
    them.
    brush: (center, radius, density), the paper's density brush: around center (3 world
        coordinates, snapped to the surface) shapes shrink to density (in (0, 1]) times their
        size and grow back linearly with the geodesic distance d from it, to their full size
        at radius: f = max(density, min(1, d / radius)), multiplying `density`'s factors.
    Returns a Distribution.
    """
    if mode not in _MODES:
        raise ValueError("mode must be one of %s, not %r" % (sorted(_MODES), mode))
    surface = as_polydata(mesh)
    table_image = tables.vtk if isinstance(tables, SafeDistanceTables) else tables
    if not isinstance(table_image, vtkImageData):
        raise TypeError("tables: a SafeDistanceTables (safe_distance_tables) or MSDT Source's tables")
    data = _copy(surface)
    nv, nf = data.GetNumberOfPoints(), data.GetNumberOfCells()
    f = vtkShapeDistributor()
    if directions is None and data.GetCellData().GetArray("Direction") is None:
        field = cross_field(data, symmetry=1)
        data = _copy(field.vtk)
    elif directions is not None:
        directions = numpy.asarray(directions, dtype=numpy.float64)
        if directions.ndim != 2 or directions.shape[1] != 3 or len(directions) not in (nf, nv):
            raise ValueError("directions: an (m, 3) array (one per triangle, m = %d) or an (n, 3) "
                             "array (one per vertex, n = %d), not %s" % (nf, nv, directions.shape))
        array = numpy_to_vtk(numpy.ascontiguousarray(directions), deep=True)
        array.SetName("GeodesicShapesDirection")
        on_cells = len(directions) == nf  # (m = n: per triangle)
        if on_cells:
            data.GetCellData().AddArray(array)
            f.SetInputArrayToProcess(0, 0, 0, vtkDataObject.FIELD_ASSOCIATION_CELLS, "GeodesicShapesDirection")
        else:
            data.GetPointData().AddArray(array)
            f.SetInputArrayToProcess(0, 0, 0, vtkDataObject.FIELD_ASSOCIATION_POINTS, "GeodesicShapesDirection")
    if symmetry is not None:
        from vtkmodules.vtkCommonCore import vtkIntArray
        array = vtkIntArray()
        array.SetName("Symmetry")
        array.InsertNextValue(int(symmetry))
        fd = data.GetFieldData()
        fd.RemoveArray("Symmetry")
        fd.AddArray(array)
    if density is not None:
        density = numpy.asarray(density, dtype=numpy.float64).reshape(-1)
        if len(density) != nv:
            raise ValueError("density: one factor per vertex (%d), not %d" % (nv, len(density)))
        array = numpy_to_vtk(density, deep=True)
        array.SetName("GeodesicShapesDensity")
        data.GetPointData().AddArray(array)
        f.SetInputArrayToProcess(1, 0, 0, vtkDataObject.FIELD_ASSOCIATION_POINTS, "GeodesicShapesDensity")
    f.SetInputData(0, data)
    f.SetInputData(1, table_image)
    f.SetShapeSize(0.0 if size is None else float(size))
    f.SetMode(_MODES[mode])
    f.SetSeed(int(seed))
    f.SetMaximumShapes(int(maximum_shapes))
    f.SetKeepInside(bool(keep_inside))
    f.SetVerifyOverlaps(bool(verify_overlaps))
    f.SetNumberOfThreads(int(threads))
    _set_engine(f, solver, _CHART_SOLVERS, k, graph_accuracy)
    if brush is not None:
        try:
            center, radius, brush_density = brush
            center = [float(x) for x in center]
        except (TypeError, ValueError):
            raise ValueError("brush: (center, radius, density) with center 3 coordinates, "
                             "not %r" % (brush,))
        if len(center) != 3:
            raise ValueError("brush: the center has 3 coordinates, not %d" % len(center))
        f.SetBrushCenter(*center)
        f.SetBrushRadius(float(radius))
        f.SetBrushDensity(float(brush_density))
    if class_weights is not None:
        weights = [float(w) for w in class_weights]
        f.SetNumberOfClassWeights(len(weights))
        for i, w in enumerate(weights):
            f.SetClassWeight(i, w)
    _update(f, "distribute_shapes", progress)
    return Distribution(f)
