"""SVG Geodesic Distance and Geodesic Polar Coordinates on pieces, without gathering: under
`mpiexec -n P pvbatch --symmetric` (P = 2, 3, and 4: one process without a piece) and a
2-process pvserver, the graph solvers, the exact solver and the virtual sources, and the exact
chart about a vertex, on a surface split in three pieces with global ids give the serial
results, each process outputs its own input cells, and no process holds the whole surface. The
same pieces without global ids (numbered as gathering them numbers them) give, under `mpiexec
-n 2`, the results of a serial run on the gathered surface.

Meshes: the bumpy sphere (closed, saddles everywhere) and the L-shaped plane (a boundary, a
regular grid: ties everywhere). Solvers: SVG (label-correcting, K = 50, unfolding refinement)
from one vertex, from two points of the Sources port (the exact distances around them on the
pieces seeding the graph search) and from a polyline, SVG (Dijkstra, K = 30, graph distances) from one vertex, and DGG (accuracy 0.01, refinement)
from two vertices with a MaximumDistance; the exact solver (window propagation on the pieces)
from two vertices, from two points of the Sources port (snapped on the pieces) and from a
polyline (sampled, snapped and traced on every process's piece, grown around it); the virtual
sources (propagation on the pieces) from two vertices and from two points (one on an edge of the
plane): as the serial run's to rounding on the plane, within 2% of the largest distance
on the bumpy sphere (VIRTUAL_SOURCES_TOLERANCE); and Geodesic Polar Coordinates about a vertex
(exact, radius 0.7, a reference direction), about a point of the Source input, and with
iso-curve angles, and the curve coordinates about a polyline: rho and theta (offset and arc
length) as the serial run's; over the whole surface (an infinite radius:
the exact distances and departure angles on the pieces) within 1e-9 (angles modulo a turn).

Bad sources (a point far from the surface, a vertex id of no point) give an error and an empty
output on every process, and the filter works again once mended.

Driver (pvpython TestMPIPieces.py --plugin P --data D --work W): splits each mesh in three
pieces with global ids (Tools/pieces.py: slabs of x + 0.3 y, not contiguous in id order), runs
the serial reference in pvbatch, then the distributed runs, and compares.
"""
import glob
import os
import shutil
import sys

import gs_test
from gs_test import check

# Tools/pieces.py: the surface split into pieces with global ids.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Tools"))
import pieces  # noqa: E402

args = gs_test.arguments(plugin=gs_test.REQUIRED, data=gs_test.REQUIRED, work=gs_test.REQUIRED,
                         run=None, meshes=None, connect=None,
                         pvbatch="pvbatch", mpiexec="mpiexec", pvserver="pvserver",
                         pvpython="pvpython")

MESHES = ["bumpy_sphere", "lshape"]
# Virtual sources on pieces: the order of processing picks between sources of nearly equal key,
# so on curved meshes the distances differ from the serial ones by up to about the method's own
# error (measured against the largest distance; the core tests check the accuracy against the
# exact solver); on flat ones they are the serial ones to rounding.
VIRTUAL_SOURCES_TOLERANCE = {"bumpy_sphere": 2e-2, "lshape": 1e-12}
PIECES = 3
TIMEOUT = 600
# (name, properties): the filters each run applies to each mesh.
# (name, filter, properties, point arrays compared): the filters each run applies to each mesh.
RUNS = [("svg", "SVGGeodesicDistance", dict(Solver="SVG (label-correcting)", K=50,
                                            SourceVertexIds=[11]), ["GeodesicDistance"]),
        ("svg-graph", "SVGGeodesicDistance", dict(Solver="SVG (Dijkstra)", K=30,
                                                  SourceVertexIds=[11], UnfoldingRefinement=0),
         ["GeodesicDistance"]),
        ("dgg", "SVGGeodesicDistance", dict(Solver="DGG (accuracy-bounded)", GraphAccuracy=0.01,
                                            SourceVertexIds=[3, 200], MaximumDistance=1.0),
         ["GeodesicDistance"]),
        ("svg-curve", "SVGGeodesicDistance",
         dict(Solver="SVG (label-correcting)", K=50,
              SourceCurve=[0.9, 0.3, 0.2, 0.5, 0.7, 0.3, 0.1, 0.9, 0.2]), ["GeodesicDistance"]),
        ("svg-points", "SVGGeodesicDistance",
         dict(Solver="SVG (label-correcting)", K=50, SourcePoints=[0.9, 0.3, 0.2, 0.2, 0.8, -0.3]),
         ["GeodesicDistance"]),
        ("exact", "SVGGeodesicDistance", dict(Solver="Exact", SourceVertexIds=[11, 200]),
         ["GeodesicDistance"]),
        ("exact-points", "SVGGeodesicDistance",
         dict(Solver="Exact", SourcePoints=[0.9, 0.3, 0.2, 0.2, 0.8, -0.3]), ["GeodesicDistance"]),
        ("exact-curve", "SVGGeodesicDistance",
         dict(Solver="Exact", SourceCurve=[0.9, 0.3, 0.2, 0.5, 0.7, 0.3, 0.1, 0.9, 0.2]),
         ["GeodesicDistance"]),
        ("vs-curve", "SVGGeodesicDistance",
         dict(Solver="Virtual sources (no precompute)",
              SourceCurve=[0.9, 0.3, 0.2, 0.5, 0.7, 0.3, 0.1, 0.9, 0.2]), ["GeodesicDistance"]),
        ("vs", "SVGGeodesicDistance", dict(Solver="Virtual sources (no precompute)",
                                           SourceVertexIds=[11, 200]), ["GeodesicDistance"]),
        ("vs-points", "SVGGeodesicDistance",
         dict(Solver="Virtual sources (no precompute)",
              SourcePoints=[0.9, 0.3, 0.2, 0.2, 0.8, -0.3]), ["GeodesicDistance"]),
        ("polar", "GeodesicPolarCoordinates", dict(SourceVertexId=11, Radius=0.7,
                                                   ReferenceDirection=[1.0, 1.0, 0.0]),
         ["GeodesicDistance", "PolarAngle"]),
        ("polar-point", "GeodesicPolarCoordinates",
         dict(SourcePoints=[0.05, 0.1, 0.6], Radius=0.7, ReferenceDirection=[1.0, 0.0, 0.0]),
         ["GeodesicDistance", "PolarAngle"]),
        ("polar-iso", "GeodesicPolarCoordinates",
         dict(SourceVertexId=11, Radius=0.6, AngleMode="Iso-curve arc length"),
         ["GeodesicDistance", "PolarAngle"]),
        ("polar-curve", "GeodesicPolarCoordinates",
         dict(SourceCurve=[0.9, 0.3, 0.2, 0.2, 0.6, 0.3, -0.3, 0.8, 0.2], Radius=0.4),
         ["Offset", "ArcLength"]),
        ("polar-whole", "GeodesicPolarCoordinates",
         dict(SourceVertexId=11, Radius=float("inf"), ReferenceDirection=[1.0, 1.0, 0.0]),
         ["GeodesicDistance", "PolarAngle"])]


# ---------------------------------------------------------------------------------------------
def run_filters():
    """One run: in pvbatch (serial or each MPI process) or connected to pvserver."""
    from paraview.simple import (PLYReader, PolyLineSource, PolyPointSource,
                                 XMLPartitionedPolydataReader, XMLPolyDataReader)
    from paraview import servermanager
    rank = gs_test.connect_run(args.connect, args.plugin, globals())
    os.makedirs(args.run, exist_ok=True)
    for mesh_file in args.meshes.split(","):
        mesh_name = os.path.basename(os.path.dirname(mesh_file)) if mesh_file.endswith(".pvtp") \
            else os.path.splitext(os.path.basename(mesh_file))[0]
        if mesh_file.endswith(".pvtp"):
            mesh = XMLPartitionedPolydataReader(FileName=[mesh_file])
        elif mesh_file.endswith(".vtp"):
            mesh = XMLPolyDataReader(FileName=[mesh_file])
        else:
            mesh = PLYReader(FileNames=[mesh_file])
        for name, filter_name, properties, _ in RUNS:
            properties = dict(properties)
            points = properties.pop("SourcePoints", None)
            curve = properties.pop("SourceCurve", None)
            distance = globals()[filter_name](Input=mesh, **properties)
            if curve is not None:
                # A polyline every process generates whole (it counts once).
                if filter_name == "GeodesicPolarCoordinates":
                    distance.Source = PolyLineSource(Points=curve)
                else:
                    distance.Sources = PolyLineSource(Points=curve)
            if points is not None:
                # Every process generates the points whole; they count once.
                if filter_name == "GeodesicPolarCoordinates":
                    distance.Source = PolyPointSource(Points=points)
                else:
                    distance.Sources = PolyPointSource(Points=points)
            distance.UpdatePipeline()
            if args.connect:
                data = servermanager.Fetch(distance)  # every process's piece, appended
            else:
                data = distance.GetClientSideObject().GetOutputDataObject(0)
            gs_test.write_polydata(data, os.path.join(args.run, "%s_%s_%d.vtp" % (mesh_name, name, rank)))
        if not args.connect:
            bad_sources(mesh, mesh_name, rank, PolyPointSource)
            switched_solver(mesh, mesh_name, rank, PolyPointSource)
    print("run %s: rank %d wrote its outputs" % (args.run, rank))
    gs_test.finish("run %s: rank %d done" % (args.run, rank))


def switched_solver(mesh, mesh_name, rank, PolyPointSource):
    """One filter switched from a graph solver to Exact with Sources points keeps its piece
    (whose band the graph made) and gives the exact-points run's distances."""
    import math
    points = dict((n, p) for n, _, p, _ in RUNS)["exact-points"]["SourcePoints"]
    distance = globals()["SVGGeodesicDistance"](Input=mesh, Solver="DGG (accuracy-bounded)",
                                                GraphAccuracy=0.1, SourceVertexIds=[11])
    distance.UpdatePipeline()
    distance.Solver = "Exact"
    distance.Sources = PolyPointSource(Points=points)
    distance.UpdatePipeline()
    if mesh.GetClientSideObject().GetOutputDataObject(0).GetNumberOfPoints() == 0:
        return  # (a process without a piece: it took part in the runs, it has nothing to compare)
    got = distance.GetClientSideObject().GetOutputDataObject(0).GetPointData().GetArray(
        "GeodesicDistance")
    expected = read(os.path.join(args.run, "%s_exact-points_%d.vtp" % (mesh_name, rank)))
    expected = expected.GetPointData().GetArray("GeodesicDistance")
    worst = max((abs(got.GetValue(i) - expected.GetValue(i)) / max(expected.GetValue(i), 1e-300)
                 for i in range(expected.GetNumberOfTuples())
                 if not math.isnan(expected.GetValue(i))), default=0.0) \
        if got is not None and expected is not None and \
        got.GetNumberOfTuples() == expected.GetNumberOfTuples() else float("inf")
    check(worst <= 1e-12, "%s, rank %d: DGG switched to Exact with points differs by %.3g" % (
        mesh_name, rank, worst))


def bad_sources(mesh, mesh_name, rank, PolyPointSource):
    """A source point far from the surface, or a vertex id of no point: an error and an empty
    output on every process (none waits for the others forever), then the mended source works."""
    for label, properties, points in (
            ("a far point", dict(Solver="Exact"), [50.0, 50.0, 50.0]),
            ("an unknown vertex id (Exact)", dict(Solver="Exact", SourceVertexIds=[10 ** 9]), None),
            ("a far point (virtual sources)", dict(Solver="Virtual sources (no precompute)"),
             [50.0, 50.0, 50.0]),
            ("an unknown vertex id (virtual sources)",
             dict(Solver="Virtual sources (no precompute)", SourceVertexIds=[10 ** 9]), None),
            ("an unknown vertex id (SVG)", dict(Solver="SVG (label-correcting)", K=30,
                                                SourceVertexIds=[10 ** 9]), None)):
        distance = globals()["SVGGeodesicDistance"](Input=mesh, **properties)
        source = PolyPointSource(Points=points) if points is not None else None
        if source is not None:
            distance.Sources = source
        errors = []
        algorithm = distance.GetClientSideObject()
        # (An observer takes the errors instead of the log, which fails a run.)
        tag = algorithm.AddObserver("ErrorEvent", lambda caller, event, *a: errors.append(event))
        distance.UpdatePipeline()
        algorithm.RemoveObserver(tag)
        data = algorithm.GetOutputDataObject(0)
        check(data.GetNumberOfPoints() == 0 and errors, "%s, rank %d, %s: an output of %d points "
              "and %d errors" % (mesh_name, rank, label, data.GetNumberOfPoints(), len(errors)))
        if source is not None:
            source.Points = [0.9, 0.3, 0.2]
        else:
            distance.SourceVertexIds = [11]
        distance.UpdatePipeline()
        data = algorithm.GetOutputDataObject(0)
        piece = mesh.GetClientSideObject().GetOutputDataObject(0).GetNumberOfPoints()
        check(data.GetNumberOfPoints() == piece, "%s, rank %d, %s: %d points after the source "
              "was mended, %d in the piece" % (mesh_name, rank, label, data.GetNumberOfPoints(),
                                               piece))


# ---------------------------------------------------------------------------------------------
def read(path):
    return gs_test.read_polydata(path)


def field(data, name):
    array = data.GetFieldData().GetAbstractArray(name)
    return array.GetVariantValue(0).ToDouble() if array is not None else None


def compare(reference, candidate, label, processes=None, faces=None):
    """Distances by point coordinates (each process's copies of shared points agree); with
    `processes`, each process's piece: its own cells, the serial mean degree, and (SVG) less
    than the whole surface held."""
    import math
    for mesh_name in MESHES:
        for name, _, _, arrays in RUNS:
            ref = read(os.path.join(reference, "%s_%s_0.vtp" % (mesh_name, name)))
            files = sorted(glob.glob(os.path.join(candidate, "%s_%s_*.vtp" % (mesh_name, name))))
            what = "%s, %s, %s" % (label, mesh_name, name)
            got = [read(f) for f in files]
            table = {}
            for data in got:
                values = [data.GetPointData().GetArray(a) for a in arrays]
                for i in range(data.GetNumberOfPoints()):
                    k = data.GetPoint(i)
                    v = [a.GetValue(i) for a in values]
                    check(k not in table or all(x == y or (math.isnan(x) and math.isnan(y))
                                                for x, y in zip(table[k], v)),
                          "%s: a point shared by two pieces has two values" % what)
                    table[k] = v
            expected = [ref.GetPointData().GetArray(a) for a in arrays]
            worst, nans, missing = 0.0, 0, 0
            virtual = name.startswith("vs")
            whole = name == "polar-whole"  # the exact solve on the pieces: equal up to rounding
            largest = max((abs(e.GetValue(i)) for e in expected for i in range(ref.GetNumberOfPoints())
                           if not math.isnan(e.GetValue(i))), default=1.0)
            for i in range(ref.GetNumberOfPoints()):
                k = ref.GetPoint(i)
                if k not in table:
                    missing += 1
                    continue
                for name_j, a, b in zip(arrays, (e.GetValue(i) for e in expected), table[k]):
                    if math.isnan(a) or math.isnan(b):
                        nans += math.isnan(a) != math.isnan(b)
                    elif whole:
                        # (Angles modulo a turn; values below 1 absolutely.)
                        d = abs(math.remainder(a - b, 2 * math.pi)) if name_j == "PolarAngle" \
                            else abs(a - b)
                        worst = max(worst, d / max(abs(a), 1.0))
                    else:
                        scale = largest if virtual else max(abs(a), 1e-300)
                        worst = max(worst, abs(a - b) / scale)
            expected = expected[0]
            reached = sum(not math.isnan(expected.GetValue(i)) for i in range(ref.GetNumberOfPoints()))
            positions = len(set(ref.GetPoint(i) for i in range(ref.GetNumberOfPoints())))
            check(missing == 0 and len(table) == positions,
                  "%s: %d points, serial %d" % (what, len(table), positions))
            check(nans == 0, "%s: %d points reached in one run only" % (what, nans))
            tolerance = (2e-2 if name == "vs-curve" else VIRTUAL_SOURCES_TOLERANCE[mesh_name]) \
                if virtual else 1e-9
            check(worst <= tolerance, "%s: %s differ by %.3g relative%s" % (
                what, "/".join(arrays), worst, " to the largest" if virtual else ""))
            check(reached > 100, "%s: only %d points reached" % (what, reached))
            line = "%s: %d points (%d reached), largest relative difference %.3g%s" % (
                what, ref.GetNumberOfPoints(), reached, worst, " (to the largest)" if virtual else "")
            if processes is not None:
                check(len(got) == processes, "%s: %d outputs" % (what, len(got)))
                held = [field(data, "PieceFaces") for data in got]
                check(all(h is not None for h in held),
                      "%s: a process gathered the surface instead of working on its piece" % what)
                check(all(field(data, "SVGMeanDegree") == field(ref, "SVGMeanDegree") and
                          field(data, "SourceAngleSum") == field(ref, "SourceAngleSum") and
                          field(data, "CurveLength") == field(ref, "CurveLength") for data in got),
                      "%s: the field data differs from the serial run's" % what)
                if name != "dgg" and all(h is not None for h in held):
                    check(max(held) < faces[mesh_name],
                          "%s: a process held %d of the %d faces" % (what, max(held), faces[mesh_name]))
                line += "; faces held per process %s of %d" % (held, faces[mesh_name])
                if name.startswith("polar"):
                    # The chart spans pieces: its values reach more than one process's cells.
                    spans = sum(any(not math.isnan(x) for x in
                                    (data.GetPointData().GetArray(arrays[-1]).GetValue(i)
                                     for i in range(data.GetNumberOfPoints()))) for data in got)
                    check(spans >= 2, "%s: the chart lies on %d process's piece" % (what, spans))
                    line += "; the chart on %d pieces" % spans
            print(line)


def gathered_surface(folder, path):
    """The pieces in `folder` (piece_0.vtp, ...) put one after another, points and cells, as
    gathering them on one process does: the surface whose point ids pieces without global ids
    keep."""
    import vtk
    append = vtk.vtkAppendPolyData()
    for piece in sorted(glob.glob(os.path.join(folder, "piece_*.vtp")),
                        key=lambda f: int(f.rsplit("_", 1)[1].split(".")[0])):
        reader = vtk.vtkXMLPolyDataReader()
        reader.SetFileName(piece)
        reader.Update()
        append.AddInputData(reader.GetOutput())
    append.Update()
    os.makedirs(os.path.dirname(path), exist_ok=True)
    gs_test.write_polydata(append.GetOutput(), path)
    return path


def driver():
    work = args.work
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    meshes = [os.path.join(args.data, m + ".ply") for m in MESHES]
    split, split_no_ids, gathered, faces, own = [], [], [], {}, {}
    for m in MESHES:
        pvtp, sizes, total = pieces.split(os.path.join(args.data, m + ".ply"), PIECES,
                                          os.path.join(work, m))
        split.append(pvtp)
        faces[m] = total
        own[m] = sizes
        split_no_ids.append(pieces.split(os.path.join(args.data, m + ".ply"), PIECES,
                                         os.path.join(work, "no_ids", m), ids=False)[0])
        gathered.append(gathered_surface(os.path.join(work, "no_ids", m),
                                         os.path.join(work, "gathered", m + ".vtp")))
    me = os.path.abspath(__file__)
    common = ["--plugin", args.plugin, "--data", args.data, "--work", work]
    env = gs_test.mpi_env()

    def run(command, label):
        gs_test.run_checked(command, label, env, TIMEOUT)

    serial = os.path.join(work, "serial")
    run([args.pvbatch, me] + common + ["--run", serial, "--meshes", ",".join(meshes)],
        "serial pvbatch")
    for p in (2, 3, 4):  # (4: more processes than pieces, one holds nothing)
        folder = os.path.join(work, "mpi%d" % p)
        run([args.mpiexec, "-n", str(p), args.pvbatch, "--symmetric", me] + common +
            ["--run", folder, "--meshes", ",".join(split)], "mpiexec -n %d pvbatch --symmetric" % p)
        compare(serial, folder, "pvbatch, %d processes" % p, processes=p, faces=faces)
        if p == 3:
            # Three processes read one piece each: each outputs exactly its input piece's cells.
            for m in MESHES:
                for name, _, _, _ in RUNS:
                    cells = [read(f).GetNumberOfCells() for f in sorted(
                        glob.glob(os.path.join(folder, "%s_%s_*.vtp" % (m, name))))]
                    check(cells == own[m], "%s, %s: output pieces of %s cells, input pieces %s"
                          % (m, name, cells, own[m]))

    # Pieces without global ids: numbered as gathering them numbers them (point ids index the
    # pieces' points one after another), on the pieces; the reference is a serial run on that
    # gathered surface.
    reference = os.path.join(work, "serial_gathered")
    run([args.pvbatch, me] + common + ["--run", reference, "--meshes", ",".join(gathered)],
        "serial pvbatch on the gathered surface")
    folder = os.path.join(work, "mpi2_no_ids")
    run([args.mpiexec, "-n", "2", args.pvbatch, "--symmetric", me] + common +
        ["--run", folder, "--meshes", ",".join(split_no_ids)],
        "mpiexec -n 2 pvbatch --symmetric, pieces without global ids")
    compare(reference, folder, "pvbatch, 2 processes, no global ids", processes=2, faces=faces)

    # A 2-process pvserver with a pvpython client (the outputs fetched to the client).
    folder = os.path.join(work, "server")
    with gs_test.PVServer(args.mpiexec, args.pvserver, 2, env) as port:
        run([args.pvpython, me] + common + ["--run", folder, "--meshes", ",".join(split),
                                            "--connect", "localhost:%d" % port],
            "pvserver, 2 processes")
    compare(serial, folder, "pvserver, 2 processes")
    gs_test.finish("TestMPIPieces passed")


if args.run:
    run_filters()
else:
    driver()
