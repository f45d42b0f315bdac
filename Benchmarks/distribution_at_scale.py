"""Shape Distributor at scale, as a ParaView user runs it (pvpython, the filter, all its outputs).

refined_elephant (libcgal-demo) subdivided once at edge midpoints (355,712 faces), the four
shapes of Data/shapes, a constant direction projected on the surface, ShapeSize 1% of the
bounding-box diagonal. Prints the first run (saddle vertex graph built) and re-runs with new
seeds (graph and distributor cached), 1 and 2 threads alternating, with the filter's own phase
split (field data PhaseSeconds of Placements) and shapes per second.

Usage: pvpython Benchmarks/distribution_at_scale.py --plugin <GeodesicShapes.so>
           [--mesh refined_elephant.off] [--size 0.01] [--runs 3] [--mode Random]
"""
import argparse
import os
import statistics
import sys
import tarfile
import tempfile
import time

import numpy
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from paraview.vtk.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkFiltersModeling import vtkLinearSubdivisionFilter
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--plugin", default=os.path.join(
    root, "build", "lib", "paraview-5.11", "plugins", "GeodesicShapes", "GeodesicShapes.so"))
parser.add_argument("--mesh", default=None, help="an OFF mesh (default: refined_elephant.off "
                    "from /usr/share/doc/libcgal-dev/data.tar.gz)")
parser.add_argument("--subdivisions", type=int, default=1)
parser.add_argument("--size", type=float, default=0.01, help="ShapeSize / bounding-box diagonal")
parser.add_argument("--runs", type=int, default=3, help="re-runs per thread count")
parser.add_argument("--mode", default="Random")
parser.add_argument("--cache", default="", help="CacheFileName of the saddle vertex graph")
parser.add_argument("--verify", action="store_true", help="VerifyOverlaps on")
parser.add_argument("--graph-accuracy", type=float, default=None,
                    help="GraphAccuracy (default: the filter's, 0.1): 0 the saddle vertex graph "
                         "of K = 50 (Solver 'SVG (label-correcting)'), else the discrete "
                         "geodesic graph of that accuracy")
parser.add_argument("--threads", type=int, nargs="+", default=[1, 2])
args = parser.parse_args()


def read_off(text):
    tokens = text.split()
    assert tokens[0] == "OFF"
    nv, nf = int(tokens[1]), int(tokens[2])
    xyz = numpy.array(tokens[4:4 + 3 * nv], dtype=float).reshape(nv, 3)
    rest = numpy.array(tokens[4 + 3 * nv:4 + 3 * nv + 4 * nf], dtype=numpy.int64).reshape(nf, 4)
    assert (rest[:, 0] == 3).all()
    return xyz, rest[:, 1:]


if args.mesh:
    with open(args.mesh) as f:
        text = f.read()
else:
    with tarfile.open("/usr/share/doc/libcgal-dev/data.tar.gz") as tar:
        text = tar.extractfile("data/meshes/refined_elephant.off").read().decode()
xyz, tris = read_off(text)
poly = vtkPolyData()
pts = vtkPoints()
pts.SetData(numpy_to_vtk(xyz, deep=True))
poly.SetPoints(pts)
cells = vtkCellArray()
offsets = numpy.arange(0, 3 * len(tris) + 1, 3, dtype=numpy.int64)
cells.SetData(numpy_to_vtkIdTypeArray(offsets, deep=True),
              numpy_to_vtkIdTypeArray(tris.reshape(-1).astype(numpy.int64), deep=True))
poly.SetPolys(cells)
if args.subdivisions > 0:
    sub = vtkLinearSubdivisionFilter()
    sub.SetNumberOfSubdivisions(args.subdivisions)
    sub.SetInputData(poly)
    sub.Update()
    poly = sub.GetOutput()
temp = tempfile.mkdtemp()
path = os.path.join(temp, "mesh.vtp")
w = vtkXMLPolyDataWriter()
w.SetDataModeToBinary()  # inline: Debian 12's expat (2.5.0-1+deb12u5) rejects large appended data
w.SetFileName(path)
w.SetInputData(poly)
w.Write()
bounds = poly.GetBounds()
diagonal = numpy.linalg.norm(numpy.array(bounds[1::2]) - numpy.array(bounds[0::2]))
print("mesh: %d vertices, %d faces, diagonal %.4g" % (poly.GetNumberOfPoints(), poly.GetNumberOfCells(), diagonal))

LoadPlugin(args.plugin, remote=False, ns=globals())
mesh = XMLPolyDataReader(FileName=[path])
field = Calculator(Input=mesh, ResultArrayName="Dir", Function="0.3*iHat+jHat+0.2*kHat")
shapes_dir = os.path.join(root, "Data", "shapes")
msdt = MSDTSource(ShapeFileNames=[os.path.join(shapes_dir, n) for n in
                                  ("star.png", "gull.png", "leaf.png", "fish.png")])
dist = ShapeDistributor(Input=field, Table=msdt, ShapeSize=args.size * diagonal, Mode=args.mode)
dist.DirectionArray = ["POINTS", "Dir"]
dist.CacheFileName = args.cache
dist.VerifyOverlaps = 1 if args.verify else 0
if args.graph_accuracy == 0:
    dist.Solver = "SVG (label-correcting)"
elif args.graph_accuracy is not None:
    dist.GraphAccuracy = args.graph_accuracy
msdt.UpdatePipeline()
field.UpdatePipeline()


def run(seed, threads):
    dist.Seed = seed
    dist.NumberOfThreads = threads
    t0 = time.perf_counter()
    dist.UpdatePipeline()
    wall = time.perf_counter() - t0
    out = dist.GetClientSideObject().GetOutputDataObject(0)
    fd = out.GetFieldData()
    phases = fd.GetArray("PhaseSeconds")
    split = {}
    if phases is not None:
        for k in range(phases.GetNumberOfComponents()):
            split[phases.GetComponentName(k)] = phases.GetComponent(0, k)
    for name in ("NumberOfCandidates", "NumberOfCharts", "OverlappingPairs", "OverlapCheckSeconds"):
        a = fd.GetArray(name)
        if a is not None:
            split[name] = a.GetValue(0)
    return wall, out.GetNumberOfPoints(), split


wall, n, split = run(1, 2)
if n == 0:
    sys.exit("no shapes placed")
print("first run (graph build, 2 threads): %.2f s, %d shapes; %s" % (
    wall, n, ", ".join("%s %.2f" % kv for kv in split.items())))
times = {1: [], 2: []}
splits = {1: [], 2: []}
counts = {1: [], 2: []}
seed = 2
for r in range(args.runs):
    for threads in args.threads:
        wall, n, split = run(seed + r, threads)
        times[threads].append(wall)
        splits[threads].append(split)
        counts[threads].append(n)
        print("re-run seed %d, %d thread(s): %.2f s, %d shapes (%.0f shapes/s); %s" % (
            seed + r, threads, wall, n, n / wall, ", ".join("%s %.2f" % kv for kv in split.items())))
for threads in args.threads:
    if not times[threads]:
        continue  # --runs 0: the first run only
    med = statistics.median(times[threads])
    names = splits[threads][0].keys() if splits[threads] else []
    print("median of %d re-runs, %d thread(s): %.2f s, %.0f shapes/s; %s" % (
        args.runs, threads, med, statistics.mean(counts[threads]) / med,
        ", ".join("%s %.2f" % (k, statistics.median(s[k] for s in splits[threads])) for k in names)))
if times[1] and times[2]:
    print("speed-up 2 threads / 1: %.2fx" % (statistics.median(times[1]) / statistics.median(times[2])))
same = not (times[1] and times[2]) or counts[1] == counts[2]
print("same counts for 1 and 2 threads:", "yes" if same else "NO")
sys.exit(0 if same else 1)
