"""Shape Distributor's edit loop as a user drives it (pvpython, the filter, all its outputs): a new
seed, the density brush moved and resized, for CandidateOrder Rounds and Place-keyed in one run.

armadillo (libcgal-demo, 52K faces) by default, the bundled star, ShapeSize 1.2% of the
bounding-box diagonal (about 900-1,000 stars), a cross field, 2 threads, the graph cached (the
first run builds it). For each edit: the wall time of the Apply, the filter's phase split (field
data PhaseSeconds), the shapes placed, the candidates decided (CandidatesRedecided) and whether
the run re-decided the edit only (IncrementalRun; an edit of a larger share of the pool than
MaximumEditShare, EditShare, runs fresh).

Usage: pvpython Benchmarks/brush_edits.py [--plugin GeodesicShapes.so] [--mesh mesh.off]
           [--size 0.012] [--brush 0.1]
"""
import argparse
import os
import tarfile
import tempfile
import time

import numpy
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from paraview.vtk.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--plugin", default=os.path.join(
    root, "build", "lib", "paraview-5.11", "plugins", "GeodesicShapes", "GeodesicShapes.so"))
parser.add_argument("--mesh", default=None, help="an OFF mesh (default: armadillo.off from "
                    "/usr/share/doc/libcgal-dev/data.tar.gz)")
parser.add_argument("--size", type=float, default=0.012, help="ShapeSize / bounding-box diagonal")
parser.add_argument("--brush", type=float, default=0.1, help="BrushRadius / bounding-box diagonal")
parser.add_argument("--threads", type=int, default=2)
args = parser.parse_args()

if args.mesh:
    with open(args.mesh) as f:
        tokens = f.read().split()
else:
    with tarfile.open("/usr/share/doc/libcgal-dev/data.tar.gz") as tar:
        tokens = tar.extractfile("data/meshes/armadillo.off").read().decode().split()
nv, nf = int(tokens[1]), int(tokens[2])
xyz = numpy.array(tokens[4:4 + 3 * nv], dtype=float).reshape(nv, 3)
tris = numpy.array(tokens[4 + 3 * nv:4 + 3 * nv + 4 * nf], dtype=numpy.int64).reshape(nf, 4)[:, 1:]
poly = vtkPolyData()
points = vtkPoints()
points.SetData(numpy_to_vtk(xyz, deep=True))
poly.SetPoints(points)
cells = vtkCellArray()
cells.SetData(numpy_to_vtkIdTypeArray(numpy.arange(0, 3 * nf + 1, 3, dtype=numpy.int64), deep=True),
              numpy_to_vtkIdTypeArray(tris.reshape(-1), deep=True))
poly.SetPolys(cells)
path = os.path.join(tempfile.mkdtemp(), "mesh.vtp")
writer = vtkXMLPolyDataWriter()
writer.SetDataModeToBinary()
writer.SetFileName(path)
writer.SetInputData(poly)
writer.Write()
diagonal = numpy.linalg.norm(xyz.max(axis=0) - xyz.min(axis=0))
print("mesh: %d vertices, %d faces" % (nv, nf))

LoadPlugin(args.plugin, remote=False, ns=globals())
mesh = XMLPolyDataReader(FileName=[path])
msdt = MSDTSource(ShapeFileNames=[os.path.join(root, "Data", "shapes", "star.png")])
field = CrossField(Input=mesh)
field.UpdatePipeline()
# Brush centres: vertices spread over the surface (the same for both orders).
centres = [xyz[i].tolist() for i in numpy.linspace(0, nv - 1, 6, dtype=int)[1:5]]


def report(label, proxy, seconds):
    data = servermanager.Fetch(proxy, idx=0)
    fd = data.GetFieldData()
    phases = fd.GetArray("PhaseSeconds")
    split = " ".join("%s %.2f" % (phases.GetComponentName(i), phases.GetComponent(0, i))
                     for i in range(phases.GetNumberOfComponents())
                     if phases.GetComponent(0, i) >= 0.005)
    print("  %-16s %5.2f s  %4d shapes  decided %7d  incremental %d (edit share %.2f)  | %s" % (
        label, seconds, data.GetNumberOfPoints(), fd.GetArray("CandidatesRedecided").GetValue(0),
        fd.GetArray("IncrementalRun").GetValue(0), fd.GetArray("EditShare").GetValue(0), split))


for order in ("Rounds", "Place-keyed (edits re-place what they reach)"):
    print(order.split(" ")[0] + ":")
    shapes = ShapeDistributor(Input=field, Table=msdt, ShapeSize=args.size * diagonal,
                              NumberOfThreads=args.threads, CandidateOrder=order)

    def apply(label):
        start = time.perf_counter()
        shapes.UpdatePipeline()
        report(label, shapes, time.perf_counter() - start)

    apply("first (graph)")
    shapes.Seed = 1
    apply("new seed")
    shapes.BrushRadius = args.brush * diagonal
    for k, centre in enumerate(centres):
        shapes.BrushCenter = centre
        apply("brush move %d" % k)
    shapes.BrushRadius = 1.2 * args.brush * diagonal
    apply("brush resize")
    Delete(shapes)
