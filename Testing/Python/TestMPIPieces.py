"""SVG Geodesic Distance on pieces, without gathering: under `mpiexec -n P pvbatch --symmetric`
(P = 2, 3) and a 2-process pvserver, the graph solvers from SourceVertexIds on a surface split in
three pieces with global ids give the serial distances, each process outputs its own input cells,
and no process holds the whole surface.

Meshes: the bumpy sphere (closed, saddles everywhere) and the L-shaped plane (a boundary, a
regular grid: ties everywhere). Solvers: SVG (label-correcting, K = 50, unfolding refinement)
and SVG (Dijkstra, K = 30, graph distances) from one vertex, and DGG (accuracy 0.01, refinement)
from two vertices with a MaximumDistance.

Driver (pvpython TestMPIPieces.py --plugin P --data D --work W): splits each mesh in three
pieces (slabs of x + 0.3 y, not contiguous in id order; a .pvtp of three .vtp with global point
and cell ids), runs the serial reference in pvbatch, then the distributed runs, and compares.
"""
import glob
import os
import socket
import shutil
import subprocess
import time

import gs_test
from gs_test import check

args = gs_test.arguments(plugin=gs_test.REQUIRED, data=gs_test.REQUIRED, work=gs_test.REQUIRED,
                         run=None, meshes=None, connect=None,
                         pvbatch="pvbatch", mpiexec="mpiexec", pvserver="pvserver",
                         pvpython="pvpython")

MESHES = ["bumpy_sphere", "lshape"]
PIECES = 3
TIMEOUT = 600
# (name, properties): the filters each run applies to each mesh.
RUNS = [("svg", dict(Solver="SVG (label-correcting)", K=50, SourceVertexIds=[11])),
        ("svg-graph", dict(Solver="SVG (Dijkstra)", K=30, SourceVertexIds=[11],
                           UnfoldingRefinement=0)),
        ("dgg", dict(Solver="DGG (accuracy-bounded)", GraphAccuracy=0.01,
                     SourceVertexIds=[3, 200], MaximumDistance=1.0))]


# ---------------------------------------------------------------------------------------------
def run_filters():
    """One run: in pvbatch (serial or each MPI process) or connected to pvserver."""
    from paraview.simple import Connect, LoadPlugin, PLYReader, XMLPartitionedPolydataReader
    from paraview import servermanager
    import vtk
    rank = 0
    if args.connect:
        host, port = args.connect.split(":")
        Connect(host, int(port))
        LoadPlugin(args.plugin, remote=True, ns=globals())
    else:
        rank = vtk.vtkMultiProcessController.GetGlobalController().GetLocalProcessId()
    LoadPlugin(args.plugin, remote=False, ns=globals())
    os.makedirs(args.run, exist_ok=True)
    for mesh_file in args.meshes.split(","):
        mesh_name = os.path.basename(os.path.dirname(mesh_file)) if mesh_file.endswith(".pvtp") \
            else os.path.splitext(os.path.basename(mesh_file))[0]
        if mesh_file.endswith(".pvtp"):
            mesh = XMLPartitionedPolydataReader(FileName=[mesh_file])
        else:
            mesh = PLYReader(FileNames=[mesh_file])
        for name, properties in RUNS:
            distance = globals()["SVGGeodesicDistance"](Input=mesh, **properties)
            distance.UpdatePipeline()
            if args.connect:
                data = servermanager.Fetch(distance)  # every process's piece, appended
            else:
                data = distance.GetClientSideObject().GetOutputDataObject(0)
            writer = vtk.vtkXMLPolyDataWriter()
            writer.SetDataModeToBinary()  # inline base64: Debian's expat rejects raw appended data
            writer.SetFileName(os.path.join(args.run, "%s_%s_%d.vtp" % (mesh_name, name, rank)))
            writer.SetInputData(data)
            writer.Write()
    print("run %s: rank %d wrote its outputs" % (args.run, rank))


# ---------------------------------------------------------------------------------------------
def read(path):
    import vtk
    reader = vtk.vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def split_mesh(mesh_file, folder):
    """PIECES slabs of the faces by x + 0.3 y of their centroids (equal counts), each with its
    used points and global point and cell ids, as a .pvtp; returns it and the pieces' cells."""
    import numpy
    import vtk
    from paraview.vtk.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    reader = vtk.vtkPLYReader()
    reader.SetFileName(mesh_file)
    reader.Update()
    whole = reader.GetOutput()
    points = vtk_to_numpy(whole.GetPoints().GetData()).astype(float)
    cells = vtk_to_numpy(whole.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    centres = points[cells].mean(axis=1)
    order = numpy.argsort(centres[:, 0] + 0.3 * centres[:, 1], kind="stable")
    part = numpy.empty(len(cells), dtype=int)
    part[order] = numpy.arange(len(cells)) * PIECES // len(cells)
    os.makedirs(folder, exist_ok=True)
    names, sizes = [], []
    for p in range(PIECES):
        mine = numpy.nonzero(part == p)[0]
        used = numpy.unique(cells[mine])
        remap = numpy.full(len(points), -1, dtype=numpy.int64)
        remap[used] = numpy.arange(len(used))
        piece = vtk.vtkPolyData()
        piece_points = vtk.vtkPoints()
        piece_points.SetData(numpy_to_vtk(points[used], deep=True))
        piece.SetPoints(piece_points)
        polys = vtk.vtkCellArray()
        polys.SetData(
            numpy_to_vtk(numpy.arange(0, 3 * len(mine) + 1, 3, dtype=numpy.int64), deep=True,
                         array_type=vtk.VTK_ID_TYPE),
            numpy_to_vtk(remap[cells[mine]].ravel(), deep=True, array_type=vtk.VTK_ID_TYPE))
        piece.SetPolys(polys)
        for attributes, ids, array_name in ((piece.GetPointData(), used, "GlobalPointIds"),
                                            (piece.GetCellData(), mine, "GlobalCellIds")):
            a = numpy_to_vtk(ids.astype(numpy.int64), deep=True, array_type=vtk.VTK_ID_TYPE)
            a.SetName(array_name)
            attributes.SetGlobalIds(a)
        name = "piece_%d.vtp" % p
        writer = vtk.vtkXMLPolyDataWriter()
        writer.SetDataModeToBinary()
        writer.SetFileName(os.path.join(folder, name))
        writer.SetInputData(piece)
        writer.Write()
        names.append(name)
        sizes.append(len(mine))
    pvtp = os.path.join(folder, "mesh.pvtp")
    with open(pvtp, "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="PPolyData" version="1.0" '
                'byte_order="LittleEndian" header_type="UInt64">\n<PPolyData GhostLevel="0">\n'
                '<PPointData GlobalIds="GlobalPointIds"><PDataArray type="Int64" '
                'Name="GlobalPointIds"/></PPointData>\n'
                '<PCellData GlobalIds="GlobalCellIds"><PDataArray type="Int64" '
                'Name="GlobalCellIds"/></PCellData>\n'
                '<PPoints><PDataArray type="Float64" NumberOfComponents="3"/></PPoints>\n')
        for n in names:
            f.write('<Piece Source="%s"/>\n' % n)
        f.write('</PPolyData>\n</VTKFile>\n')
    return pvtp, sizes, len(cells)


def field(data, name):
    array = data.GetFieldData().GetAbstractArray(name)
    return array.GetVariantValue(0).ToDouble() if array is not None else None


def compare(reference, candidate, label, processes=None, faces=None):
    """Distances by point coordinates (each process's copies of shared points agree); with
    `processes`, each process's piece: its own cells, the serial mean degree, and (SVG) less
    than the whole surface held."""
    import math
    for mesh_name in MESHES:
        for name, _ in RUNS:
            ref = read(os.path.join(reference, "%s_%s_0.vtp" % (mesh_name, name)))
            files = sorted(glob.glob(os.path.join(candidate, "%s_%s_*.vtp" % (mesh_name, name))))
            what = "%s, %s, %s" % (label, mesh_name, name)
            got = [read(f) for f in files]
            table = {}
            for data in got:
                d = data.GetPointData().GetArray("GeodesicDistance")
                for i in range(data.GetNumberOfPoints()):
                    k = data.GetPoint(i)
                    v = d.GetValue(i)
                    check(k not in table or table[k] == v or (math.isnan(v) and math.isnan(table[k])),
                          "%s: a point shared by two pieces has two values" % what)
                    table[k] = v
            expected = ref.GetPointData().GetArray("GeodesicDistance")
            worst, nans, missing = 0.0, 0, 0
            for i in range(ref.GetNumberOfPoints()):
                k = ref.GetPoint(i)
                if k not in table:
                    missing += 1
                    continue
                a, b = expected.GetValue(i), table[k]
                if math.isnan(a) or math.isnan(b):
                    nans += math.isnan(a) != math.isnan(b)
                else:
                    worst = max(worst, abs(a - b) / max(abs(a), 1e-300))
            reached = sum(not math.isnan(expected.GetValue(i)) for i in range(ref.GetNumberOfPoints()))
            check(missing == 0 and len(table) == ref.GetNumberOfPoints(),
                  "%s: %d points, serial %d" % (what, len(table), ref.GetNumberOfPoints()))
            check(nans == 0, "%s: %d points reached in one run only" % (what, nans))
            check(worst <= 1e-9, "%s: distances differ by %.3g relative" % (what, worst))
            check(reached > 100, "%s: only %d points reached" % (what, reached))
            line = "%s: %d points (%d reached), largest relative difference %.3g" % (
                what, ref.GetNumberOfPoints(), reached, worst)
            if processes is not None:
                check(len(got) == processes, "%s: %d outputs" % (what, len(got)))
                held = [field(data, "PieceFaces") for data in got]
                check(all(h is not None for h in held),
                      "%s: a process gathered the surface instead of working on its piece" % what)
                check(all(field(data, "SVGMeanDegree") == field(ref, "SVGMeanDegree") for data in got),
                      "%s: the graph's mean degree differs from the serial graph's" % what)
                if name.startswith("svg") and all(h is not None for h in held):
                    check(max(held) < faces[mesh_name],
                          "%s: a process held %d of the %d faces" % (what, max(held), faces[mesh_name]))
                line += "; faces held per process %s of %d" % (held, faces[mesh_name])
            print(line)


def driver():
    work = args.work
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    meshes = [os.path.join(args.data, m + ".ply") for m in MESHES]
    split, faces, own = [], {}, {}
    for m in MESHES:
        pvtp, sizes, total = split_mesh(os.path.join(args.data, m + ".ply"), os.path.join(work, m))
        split.append(pvtp)
        faces[m] = total
        own[m] = sizes
    me = os.path.abspath(__file__)
    common = ["--plugin", args.plugin, "--data", args.data, "--work", work]
    env = gs_test.mpi_env()

    def run(command, label):
        start = time.time()
        result = subprocess.run(command, env=env, timeout=TIMEOUT, stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, universal_newlines=True)
        print("%s: %.1f s" % (label, time.time() - start))
        passed = result.returncode == 0 and "ERR|" not in result.stdout
        if not passed:
            print(result.stdout)
        check(passed, "%s failed (exit %d%s)" % (label, result.returncode,
                                                ", ParaView errors" if "ERR|" in result.stdout else ""))
        if not passed:
            gs_test.finish()

    serial = os.path.join(work, "serial")
    run([args.pvbatch, me] + common + ["--run", serial, "--meshes", ",".join(meshes)],
        "serial pvbatch")
    for p in (2, 3):
        folder = os.path.join(work, "mpi%d" % p)
        run([args.mpiexec, "-n", str(p), args.pvbatch, "--symmetric", me] + common +
            ["--run", folder, "--meshes", ",".join(split)], "mpiexec -n %d pvbatch --symmetric" % p)
        compare(serial, folder, "pvbatch, %d processes" % p, processes=p, faces=faces)
        if p == 3:
            # Three processes read one piece each: each outputs exactly its input piece's cells.
            for m in MESHES:
                for name, _ in RUNS:
                    cells = [read(f).GetNumberOfCells() for f in sorted(
                        glob.glob(os.path.join(folder, "%s_%s_*.vtp" % (m, name))))]
                    check(cells == own[m], "%s, %s: output pieces of %s cells, input pieces %s"
                          % (m, name, cells, own[m]))

    # A 2-process pvserver with a pvpython client (the outputs fetched to the client).
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    server = subprocess.Popen([args.mpiexec, "-n", "2", args.pvserver, "--server-port=%d" % port],
                              env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              universal_newlines=True)
    try:
        deadline = time.time() + 120
        ready = False
        while time.time() < deadline:
            line = server.stdout.readline()
            if not line:
                break
            if "Accepting connection" in line:
                ready = True
                break
        check(ready, "pvserver did not start")
        if ready:
            folder = os.path.join(work, "server")
            run([args.pvpython, me] + common + ["--run", folder, "--meshes", ",".join(split),
                                                "--connect", "localhost:%d" % port],
                "pvserver, 2 processes")
            compare(serial, folder, "pvserver, 2 processes")
    finally:
        server.terminate()
        try:
            server.wait(timeout=30)
        except subprocess.TimeoutExpired:
            server.kill()
    gs_test.finish("TestMPIPieces passed")


if args.run:
    run_filters()
else:
    driver()
