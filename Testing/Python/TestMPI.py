"""Distributed execution: every filter of the Fig. 1 pipeline gives the serial result under
`mpiexec -n 2 pvbatch --symmetric` and through a 2-process pvserver.

Pipeline (as Examples/main_job.py): Cross Field (Prescribed singularities at the poles, a stroke
along the equator) -> SVG Geodesic Distance (brush at a vertex id) -> Calculator (Density) ->
Shape Distributor (MSDT Source tables of the four bundled shapes, Greedy), plus Geodesic Polar
Coordinates from a Source point.

Driver (pvpython TestMPI.py --plugin P --data D --work W): splits the bundled bumpy sphere into
two pieces along a plane (a .pvtp of two .vtp, with global point and cell ids), then runs
  1. serial: pvbatch on the original mesh (the reference),
  2. mpi:    mpiexec -n 2 pvbatch --symmetric on the pieces (each process writes its outputs),
  3. server: pvpython connected to mpiexec -n 2 pvserver, on the pieces (outputs fetched),
  4. mpi-noids: the pieces without global ids, against pvbatch reading the same pieces serially
     (the reassembled surface is then the serial reader's: piece 0, then piece 1),
and compares point and cell arrays (matched by coordinates) and the placed shapes.
"""
import glob
import os
import shutil
import sys

import gs_test
from gs_test import check

# Tools/pieces.py: a surface written as pieces with global ids.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Tools"))
import pieces as surface_pieces  # noqa: E402

# The driver's options, and the sub-runs' (which the driver passes with the common ones):
#   --run      one run: write its outputs into this folder
#   --mesh     the run's input mesh (.ply or .pvtp)
#   --connect  host:port of a pvserver to run on
#   --brush    the brush vertex id (a serial vertex id)
args = gs_test.arguments(plugin=gs_test.REQUIRED, data=gs_test.REQUIRED, work=gs_test.REQUIRED,
                         run=None, mesh=None, connect=None, brush=-1,
                         pvbatch="pvbatch", mpiexec="mpiexec", pvserver="pvserver",
                         pvpython="pvpython")
args.brush = int(args.brush)

SHAPES = ["star.png", "gull.png", "leaf.png", "fish.png"]
TIMEOUT = 600


# ---------------------------------------------------------------------------------------------
def run_pipeline():
    """One run of the pipeline: in pvbatch (serial or each MPI process) or connected to pvserver."""
    from paraview.simple import (Calculator, PLYReader, PointSource, PolyLineSource,
                                 ProgrammableSource, SetActiveSource, XMLPartitionedPolydataReader)
    from paraview import servermanager

    rank = gs_test.connect_run(args.connect, args.plugin, globals())
    CrossField, SVGGeodesicDistance, GeodesicPolarCoordinates, MSDTSource, ShapeDistributor = (
        globals()[n] for n in ("CrossField", "SVGGeodesicDistance", "GeodesicPolarCoordinates",
                               "MSDTSource", "ShapeDistributor"))
    os.makedirs(args.run, exist_ok=True)

    if args.mesh.endswith(".pvtp"):
        mesh = XMLPartitionedPolydataReader(FileName=[args.mesh])
    else:
        mesh = PLYReader(FileNames=[args.mesh])
    # The bumpy sphere: centre 0, radius about 1 (fixed here: no data information is needed).
    poles = ProgrammableSource(OutputDataSetType="vtkPolyData")
    poles.Script = """
import vtk
pts = vtk.vtkPoints()
pts.InsertNextPoint(0.0, 0.0, 1.3)
pts.InsertNextPoint(0.0, 0.0, -1.3)
idx = vtk.vtkDoubleArray()
idx.SetName("Index")
idx.InsertNextValue(1.0)
idx.InsertNextValue(1.0)
out = self.GetPolyDataOutput()
out.SetPoints(pts)
out.GetPointData().AddArray(idx)
"""
    import math
    stroke = PolyLineSource(Points=sum(([math.cos(t), math.sin(t), 0.25 * math.sin(2 * t)]
                                        for t in [-0.6 + 0.1 * k for k in range(13)]), []))
    field = CrossField(Input=mesh, Singularities=poles, Strokes=stroke, Symmetry=1,
                       Mode="Prescribed singularities")
    # (A graph solver: its distances on pieces are the serial ones, so the shapes placed with them
    # are too; the default virtual sources' depend a little on the partition.)
    distance = SVGGeodesicDistance(Input=field, SourceVertexIds=[args.brush],
                                   Solver="SVG (label-correcting)")
    density = Calculator(Input=distance, ResultArrayName="Density",
                         Function="max(0.45, min(1.0, GeodesicDistance / 0.9))")
    polar = GeodesicPolarCoordinates(Input=density, Radius=0.8)
    polar.Source = PointSource(Center=[0.0, 0.0, 1.0], NumberOfPoints=1, Radius=0.0)
    msdt = MSDTSource(ShapeFileNames=[os.path.join(args.data, "shapes", s) for s in SHAPES],
                      AngleBins=48, DistanceSteps=48, TextureSize=64)
    shapes = ShapeDistributor(Input=density, Table=msdt, ShapeSize=0.12, Mode="Greedy", Seed=3)
    shapes.DirectionArray = ["CELLS", "Direction"]
    shapes.DensityArray = ["POINTS", "Density"]
    shapes.ClassWeights = [1.0] * len(SHAPES)

    outputs = [("polar", polar, 0), ("placements", shapes, 0), ("outlines", shapes, 2)]
    for name, proxy, port in outputs:
        proxy.UpdatePipeline()
        if args.connect:
            data = servermanager.Fetch(proxy, idx=port)  # every process's piece, appended
        else:
            data = proxy.GetClientSideObject().GetOutputDataObject(port)  # this process's piece
        if data.GetNumberOfPoints() == 0:
            continue  # an empty piece (the shapes live on process 0)
        gs_test.write_polydata(data, os.path.join(args.run, "%s_%d.vtp" % (name, rank)))
    print("run %s: rank %d wrote its outputs" % (args.run, rank))


# ---------------------------------------------------------------------------------------------
def read(path):
    return gs_test.read_polydata(path)


def pieces(folder, name):
    return [read(f) for f in sorted(glob.glob(os.path.join(folder, name + "_*.vtp")))]


def split_mesh(mesh_file, folder, ids):
    """Two pieces of the mesh (cells by the sign of x + 0.3 y: not contiguous in id order), each
    with its used points (shared ones repeated), global ids when `ids`, as a .pvtp."""
    import numpy
    from paraview.vtk.util.numpy_support import vtk_to_numpy
    whole = surface_pieces.read_surface(mesh_file)
    points = vtk_to_numpy(whole.GetPoints().GetData()).astype(float)
    cells = vtk_to_numpy(whole.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    centres = points[cells].mean(axis=1)
    part = numpy.where(centres[:, 0] + 0.3 * centres[:, 1] >= 0.0, 0, 1)
    return surface_pieces.write_pieces(whole, part, folder, ids)[0]


def input_pieces(pvtp):
    """Cells of each piece of a .pvtp: what each process's output piece must hold."""
    folder = os.path.dirname(pvtp)
    return [read(os.path.join(folder, "piece_%d.vtp" % k)).GetNumberOfCells() for k in range(2)]


def key_point(x):
    return tuple(round(v, 12) for v in x)


def compare(reference, candidate, label, expected_pieces=None):
    """Point and cell arrays of the polar output, then placements and outlines."""
    import numpy
    from paraview.vtk.util.numpy_support import vtk_to_numpy
    failed_before = len(gs_test.failures)
    ref = pieces(reference, "polar")
    got = pieces(candidate, "polar")
    if expected_pieces is not None:
        sizes = [p.GetNumberOfCells() for p in got]
        check(sizes == expected_pieces, "%s: pieces of %s cells, expected each process's input piece %s"
              % (label, sizes, expected_pieces))
    ref_points, got_points = {}, {}
    for pieces_, table in ((ref, ref_points), (got, got_points)):
        for data in pieces_:
            pd = data.GetPointData()
            for i in range(data.GetNumberOfPoints()):
                values = []
                for name in ("GeodesicDistance", "Density", "PolarRadius", "PolarAngle"):
                    array = pd.GetArray(name)
                    values.append(array.GetTuple1(i) if array else float("inf"))
                k = key_point(data.GetPoint(i))
                check(k not in table or numpy.allclose(table[k], values, rtol=0, atol=1e-9,
                                                       equal_nan=True),
                      "%s: a point shared by two pieces has two values" % label)
                table[k] = values
    check(set(ref_points) == set(got_points),
          "%s: %d points, serial %d" % (label, len(got_points), len(ref_points)))
    worst = 0.0
    for k, values in ref_points.items():
        if k in got_points:
            a, b = numpy.array(values), numpy.array(got_points[k])
            both = numpy.isfinite(a) & numpy.isfinite(b)
            same_nans = not (numpy.isfinite(a) != numpy.isfinite(b)).any()
            check(same_nans, "%s: NaN pattern differs at %s" % (label, k))
            if not same_nans:
                break  # one such point is reported
            if both.any():
                worst = max(worst, float(numpy.abs(a[both] - b[both]).max()))
    check(worst <= 1e-9, "%s: point arrays differ by %.3g" % (label, worst))

    def cells(pieces_):
        table = {}
        for data in pieces_:
            direction = data.GetCellData().GetArray("Direction")
            has_direction = not data.GetNumberOfCells() or direction is not None
            check(has_direction, "%s: no Direction cell array" % label)
            if not has_direction:
                return table
            for c in range(data.GetNumberOfCells()):
                ids = data.GetCell(c).GetPointIds()
                k = tuple(sorted(key_point(data.GetPoint(ids.GetId(j))) for j in range(3)))
                table[k] = direction.GetTuple3(c)
        return table
    ref_cells, got_cells = cells(ref), cells(got)
    same_cells = set(ref_cells) == set(got_cells)
    check(same_cells, "%s: %d cells, serial %d" % (label, len(got_cells), len(ref_cells)))
    if same_cells:
        d = max(max(abs(a - b) for a, b in zip(ref_cells[k], got_cells[k])) for k in ref_cells)
        check(d <= 1e-9, "%s: Direction differs by %.3g" % (label, d))

    for name, arrays in (("placements", ("ClassId", "Scale", "Direction", "FaceId")),
                         ("outlines", ("ShapeId", "ClassId"))):
        ref_d = [p for p in pieces(reference, name) if p.GetNumberOfPoints()]
        got_d = [p for p in pieces(candidate, name) if p.GetNumberOfPoints()]
        on_process_0 = len(ref_d) == 1 and len(got_d) == 1
        check(on_process_0, "%s: %s on %d processes (serial %d; expected all on process 0)"
              % (label, name, len(got_d), len(ref_d)))
        if not on_process_0:
            continue
        a, b = ref_d[0], got_d[0]
        same_size = ((a.GetNumberOfPoints(), a.GetNumberOfCells())
                     == (b.GetNumberOfPoints(), b.GetNumberOfCells()))
        check(same_size, "%s: %s has %d points / %d cells, serial %d / %d" % (
            label, name, b.GetNumberOfPoints(), b.GetNumberOfCells(), a.GetNumberOfPoints(),
            a.GetNumberOfCells()))
        if not same_size:
            continue
        pa = vtk_to_numpy(a.GetPoints().GetData())
        pb = vtk_to_numpy(b.GetPoints().GetData())
        check(abs(pa - pb).max() <= 1e-9,
              "%s: %s points differ by %.3g" % (label, name, abs(pa - pb).max()))
        for array in arrays:
            attributes_a = a.GetPointData() if name == "placements" else a.GetCellData()
            attributes_b = b.GetPointData() if name == "placements" else b.GetCellData()
            va = vtk_to_numpy(attributes_a.GetArray(array)).astype(float)
            vb = vtk_to_numpy(attributes_b.GetArray(array)).astype(float)
            check(abs(va - vb).max() <= 1e-9, "%s: %s %s differs" % (label, name, array))
    placed = [p for p in pieces(reference, "placements") if p.GetNumberOfPoints()]
    n_shapes = placed[0].GetNumberOfPoints() if placed else 0
    check(n_shapes >= 50, "%s: only %d shapes in the serial run" % (label, n_shapes))
    identical = len(gs_test.failures) == failed_before
    print("%s: %d points, %d cells, %d shapes compared with the serial run; %s" % (
        label, len(ref_points), len(ref_cells), n_shapes, "identical" if identical else "DIFFERENT"))


def driver():
    import vtk
    work = args.work
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    mesh = os.path.join(args.data, "bumpy_sphere.ply")
    with_ids = split_mesh(mesh, os.path.join(work, "pieces"), True)
    without_ids = split_mesh(mesh, os.path.join(work, "pieces_noids"), False)
    # The brush vertex: the one nearest (0, -1, 0), a serial vertex id.
    reader = vtk.vtkPLYReader()
    reader.SetFileName(mesh)
    reader.Update()
    locator = vtk.vtkPointLocator()
    locator.SetDataSet(reader.GetOutput())
    brush = locator.FindClosestPoint(0.0, -1.0, 0.0)
    me = os.path.abspath(__file__)
    common = ["--plugin", args.plugin, "--data", args.data, "--work", work, "--brush", str(brush)]
    env = gs_test.mpi_env()
    mpi = [args.mpiexec, "-n", "2"]

    def run(command, label):
        gs_test.run_checked(command, label, env, TIMEOUT)

    folders = {k: os.path.join(work, k) for k in ("serial", "mpi", "server", "serial-noids", "mpi-noids")}
    run([args.pvbatch, me] + common + ["--run", folders["serial"], "--mesh", mesh], "serial pvbatch")
    run(mpi + [args.pvbatch, "--symmetric", me] + common + ["--run", folders["mpi"], "--mesh", with_ids],
        "mpiexec -n 2 pvbatch --symmetric")
    compare(folders["serial"], folders["mpi"], "pvbatch, 2 processes, global ids",
            input_pieces(with_ids))

    # pvserver with 2 processes, a pvpython client.
    with gs_test.PVServer(args.mpiexec, args.pvserver, 2, env) as port:
        run([args.pvpython, me] + common + ["--run", folders["server"], "--mesh", with_ids,
                                         "--connect", "localhost:%d" % port], "pvserver, 2 processes")
    compare(folders["serial"], folders["server"], "pvserver, 2 processes, global ids")

    # Without global ids: the reassembled surface is the serial reader's (piece 0 then piece 1).
    run([args.pvbatch, me] + common + ["--run", folders["serial-noids"], "--mesh", without_ids],
        "serial pvbatch, pieces without ids")
    run(mpi + [args.pvbatch, "--symmetric", me] + common + ["--run", folders["mpi-noids"], "--mesh",
                                                           without_ids],
        "mpiexec -n 2 pvbatch --symmetric, pieces without ids")
    compare(folders["serial-noids"], folders["mpi-noids"], "pvbatch, 2 processes, no ids",
            input_pieces(without_ids))
    gs_test.finish("TestMPI passed")


if args.run:
    run_pipeline()
else:
    driver()
