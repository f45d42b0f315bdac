"""SVG Geodesic Distance on a surface spread over MPI processes: memory and time per process
count, on pieces (nothing gathered) against the serial run and the gathering route.

For the mesh (a file, or `file:S` subdivided S times at edge midpoints) and each process count P,
the faces are split into P slabs with global ids (Tools/pieces.py; Debian's ParaView 5.11 cannot
run Redistribute DataSet: its expat rejects the raw binary the filter writes between processes). Then, in
separate processes with nothing else running:
  serial   pvbatch on the whole mesh (the reference distances and memory);
  pieces   mpiexec -n P pvbatch --symmetric from SourceVertexIds: each process works on its
           piece and a band of its neighbours' faces (vtkSurfacePieces);
  gather   (graph solvers) the same source given as a point on the Sources port, which
           gathers the surface on process 0 and builds the graph there (what every run did
           before the pieces route; a point source at a vertex is that vertex: the same
           distances).
Both with unfolding refinement (the default), or without it with --no-refine.
Per process: peak resident memory added by the filter (the process's peak during the first Apply,
its VmHWM reset just before, minus its resident memory before) and that whole peak (ParaView,
the reader's output and the filter), the first Apply (band, graph, solve), a further source, the
faces the process held.
OMP_NUM_THREADS is 2 / P (at least 1): P > 2 oversubscribes the 2-core machine, and is marked so.

    pvpython Benchmarks/mpi_pieces.py --plugin build/lib/paraview-5.11/plugins/GeodesicShapes/GeodesicShapes.so \\
        build/bench-data/data/meshes/refined_elephant.off:2 --processes 1 2 4 [--solver svg|dgg|exact|vs]
"""
import argparse
import glob
import json
import os
import subprocess
import sys
import tempfile
import time

SOLVERS = {"svg": {"Solver": "SVG (label-correcting)", "K": 50},
           "dgg": {"Solver": "DGG (accuracy-bounded)", "GraphAccuracy": 0.1},
           "exact": {"Solver": "Exact"},
           "vs": {"Solver": "Virtual sources (no precompute)"}}
SOURCES = [0, 1000]  # serial vertex ids: the first Apply, then a further source


def status_kb(field):
    """A memory figure of this process from /proc/self/status, in kB."""
    import re
    with open("/proc/self/status") as f:
        return int(re.search(field + r":\s+(\d+)", f.read()).group(1))


def run_one(args):
    """One process of a run: the pipeline, then its figures (a JSON file per process)."""
    from paraview.simple import LoadPlugin, PLYReader, XMLPartitionedPolydataReader
    import vtk
    LoadPlugin(args.plugin, remote=False, ns=globals())
    controller = vtk.vtkMultiProcessController.GetGlobalController()
    rank = controller.GetLocalProcessId() if controller else 0
    if args.mesh.endswith(".pvtp"):
        mesh = XMLPartitionedPolydataReader(FileName=[args.mesh])
    else:
        mesh = PLYReader(FileNames=[args.mesh])
    mesh.UpdatePipeline()
    # The process's peak from here on (Linux: writing 5 to clear_refs resets VmHWM).
    with open("/proc/self/clear_refs", "w") as f:
        f.write("5")
    before = status_kb("VmRSS")
    distance = globals()["SVGGeodesicDistance"](Input=mesh, SourceVertexIds=[SOURCES[0]],
                                               UnfoldingRefinement=int(args.refine),
                                               **SOLVERS[args.solver])
    if args.gather:
        # The same vertex as a point on the Sources port: the gathering route.
        from paraview.simple import PointSource
        distance.Sources = PointSource(Center=args.gather, NumberOfPoints=1, Radius=0.0)
    start = time.perf_counter()
    distance.UpdatePipeline()
    first = time.perf_counter() - start
    peak = status_kb("VmHWM")
    data = distance.GetClientSideObject().GetOutputDataObject(0)
    writer = vtk.vtkXMLPolyDataWriter()
    writer.SetDataModeToBinary()
    writer.SetFileName(os.path.join(args.out, "distance_%d.vtp" % rank))
    writer.SetInputData(data)
    writer.Write()
    distance.SourceVertexIds = [SOURCES[1]]
    if args.gather:
        distance.Sources.Center = args.gather2
    start = time.perf_counter()
    distance.UpdatePipeline()
    further = time.perf_counter() - start
    faces = data.GetFieldData().GetArray("PieceFaces")
    with open(os.path.join(args.out, "figures_%d.json" % rank), "w") as f:
        f.write(json.dumps({
        "rank": rank, "first": first, "further": further, "peak_mb": (peak - before) / 1024.0,
        "process_mb": peak / 1024.0,
        "cells": data.GetNumberOfCells(),
        "held": faces.GetValue(0) if faces is not None else None}))


def distances(folder):
    """Distances by point coordinates over a run's output pieces."""
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    table = {}
    for path in sorted(glob.glob(os.path.join(folder, "distance_*.vtp"))):
        reader = vtk.vtkXMLPolyDataReader()
        reader.SetFileName(path)
        reader.Update()
        data = reader.GetOutput()
        xyz = vtk_to_numpy(data.GetPoints().GetData())
        d = vtk_to_numpy(data.GetPointData().GetArray("GeodesicDistance"))
        table.update(zip(map(tuple, xyz.tolist()), d.tolist()))
    return table


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("mesh", nargs="?")
    parser.add_argument("--plugin", required=True)
    parser.add_argument("--processes", type=int, nargs="+", default=[1, 2, 4])
    parser.add_argument("--solver", choices=sorted(SOLVERS), default="svg")
    parser.add_argument("--no-gather", action="store_true", help="skip the gathering runs")
    parser.add_argument("--cores", type=int, default=os.cpu_count())
    # One process of a run (internal).
    parser.add_argument("--one", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--refine", type=int, default=1, help=argparse.SUPPRESS)
    parser.add_argument("--gather", type=float, nargs=3, help=argparse.SUPPRESS)
    parser.add_argument("--gather2", type=float, nargs=3, help=argparse.SUPPRESS)
    parser.add_argument("--no-refine", action="store_true", help="graph distances only")
    parser.add_argument("--out", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.one:
        run_one(args)
        return

    here = os.path.dirname(os.path.abspath(__file__))
    sys.path.insert(0, here)
    sys.path.insert(0, os.path.join(here, "..", "Tools"))
    from geodesic_engines import mesh_file  # noqa: E402
    import pieces  # noqa: E402
    import math
    work = tempfile.mkdtemp(prefix="gs_mpi_pieces_")
    ply = mesh_file(args.mesh, work)
    me = os.path.abspath(__file__)
    env = {k: v for k, v in os.environ.items()
           if not k.startswith(("OMPI_", "PMIX_", "ORTE_", "OPAL_"))}
    env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1", OMPI_MCA_mpi_yield_when_idle="1")

    refine = 0 if args.no_refine else 1

    def run(label, processes, mesh, gather=False):
        out = os.path.join(work, label)
        os.makedirs(out, exist_ok=True)
        command = ["pvbatch", me, mesh, "--plugin", args.plugin, "--solver", args.solver,
                   "--one", "--refine", str(refine), "--out", out]
        if gather:
            command += ["--gather"] + ["%.17g" % c for c in source_points[0]]
            command += ["--gather2"] + ["%.17g" % c for c in source_points[1]]
        if processes > 1:
            command = ["mpiexec", "-n", str(processes), "pvbatch", "--symmetric"] + command[1:]
        env["OMP_NUM_THREADS"] = str(max(1, args.cores // processes))
        result = subprocess.run(command, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                universal_newlines=True)
        figures = []
        for path in glob.glob(os.path.join(out, "figures_*.json")):
            with open(path) as f:
                figures.append(json.load(f))
        figures.sort(key=lambda f: f["rank"])
        if result.returncode != 0 or len(figures) != processes:
            print(result.stdout)
            sys.exit("%s failed" % label)
        return out, figures

    import vtk
    reader = vtk.vtkPLYReader()
    reader.SetFileName(ply)
    reader.Update()
    source_points = [reader.GetOutput().GetPoint(v) for v in SOURCES]
    del reader
    reference, serial = run("serial", 1, ply)
    ref = distances(reference)
    nfaces = None
    print("%s, %s, unfolding refinement %s; peak = resident memory added by the filter; "
          "first = first Apply (band, graph, solve); further = another source"
          % (args.mesh, SOLVERS[args.solver], "on" if refine else "off"))
    print("%-26s %6s %10s %16s %9s %9s %12s %s" % ("run", "P", "peak MB", "process peak MB",
                                                   "first s", "next s", "faces held",
                                                   "largest rel. difference"))

    def report(label, p, figures, out):
        got = distances(out)
        pairs = [(got[k], v) for k, v in ref.items()
                 if k in got and v > 0 and math.isfinite(v) and math.isfinite(got[k])]
        worst = max((abs(g - v) / v for g, v in pairs), default=0.0)
        largest = max((v for _, v in pairs), default=1.0)
        worst_abs = max((abs(g - v) for g, v in pairs), default=0.0) / largest
        flag = " (oversubscribed)" if p > args.cores else ""
        print("%-26s %6d %10s %16s %9.2f %9.2f %12s %.3g (%.3g of the largest)%s" % (
            label, p, "/".join("%.0f" % f["peak_mb"] for f in figures),
            "/".join("%.0f" % f["process_mb"] for f in figures),
            max(f["first"] for f in figures), max(f["further"] for f in figures),
            "/".join(str(f["held"]) for f in figures) if figures[0]["held"] is not None else "-",
            worst, worst_abs, flag))

    report("serial", 1, serial, reference)
    for p in args.processes:
        if p < 2:
            continue
        pvtp, _, nfaces = pieces.split(ply, p, os.path.join(work, "split%d" % p))
        out, figures = run("pieces%d" % p, p, pvtp)
        report("pieces (nothing gathered)", p, figures, out)
        # (The exact and virtual-source solvers take source points on the pieces too: no
        # gathering route to compare with.)
        if not args.no_gather and args.solver not in ("exact", "vs"):
            out, figures = run("gather%d" % p, p, pvtp, gather=True)
            report("gather (point source)", p, figures, out)
    print("faces: %s; outputs in %s" % (nfaces, work))


if __name__ == "__main__":
    main()
