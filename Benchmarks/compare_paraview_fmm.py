"""ParaView's own geodesic filter against ours, in pvpython, on the same meshes and sources.

ParaView ships the GeodesicMeasurement plugin with a fast-marching filter,
"Fast-Marching Geodesic Distance-Field From Binary Field" (seeds: the non-zero points of a point
array). For each mesh and source vertex this script runs it, our SVG solver and our exact solver
(the reference), and prints the mean/max relative error against the exact distances and the
time per solve (the SVG graph build is reported separately: it happens once per mesh).

    xvfb-run -a pvpython Benchmarks/compare_paraview_fmm.py --plugin build/lib/.../GeodesicShapes.so \
        mesh.off mesh.ply ... [--sources 3] [--k 50]
"""
import argparse
import os
import sys
import tempfile
import time

import numpy as np
from paraview import servermanager as sm
from paraview.simple import *  # noqa: F401,F403
from vtkmodules.numpy_interface import dataset_adapter as dsa

PARAVIEW_FMM = "/usr/lib/x86_64-linux-gnu/paraview-5.11/plugins/GeodesicMeasurement/GeodesicMeasurement.so"


def off_to_ply(path, folder):
    """ParaView has no OFF reader: rewrite the file as ASCII PLY (same vertices, same order)."""
    with open(path) as f:
        tokens = []
        for line in f:
            line = line.split("#")[0].strip()
            if line:
                tokens.append(line)
    header = tokens[0].split()
    if header[0].endswith("OFF") and len(header) == 1:
        counts = tokens[1].split()
        body = tokens[2:]
    else:
        counts = header[1:]
        body = tokens[1:]
    nv, nf = int(counts[0]), int(counts[1])
    out = os.path.join(folder, os.path.basename(path) + ".ply")
    with open(out, "w") as f:
        f.write("ply\nformat ascii 1.0\nelement vertex %d\nproperty double x\nproperty double y\n"
                "property double z\nelement face %d\nproperty list uchar int vertex_indices\n"
                "end_header\n" % (nv, nf))
        for line in body[:nv]:
            f.write(" ".join(line.split()[:3]) + "\n")
        for line in body[nv:nv + nf]:
            f.write(line + "\n")
    return out


def fetch_array(proxy, name):
    data = dsa.WrapDataObject(sm.Fetch(proxy))
    return np.array(data.PointData[name], dtype=float)


def timed_update(proxy):
    start = time.perf_counter()
    proxy.UpdatePipeline()
    return time.perf_counter() - start


def errors(approx, exact):
    mask = np.isfinite(exact) & (exact > 0)
    rel = np.abs(approx[mask] - exact[mask]) / exact[mask]
    return rel.mean(), rel.max()


SEED_SCRIPT = """
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
inp = self.GetInputDataObject(0, 0)
out = self.GetOutputDataObject(0)
out.ShallowCopy(inp)
seed = np.zeros(inp.GetNumberOfPoints())
seed[%d] = 1.0
array = numpy_to_vtk(seed, deep=1)
array.SetName("Seed")
out.GetPointData().AddArray(array)
"""


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("meshes", nargs="+")
    parser.add_argument("--plugin", required=True, help="path to GeodesicShapes.so")
    parser.add_argument("--sources", type=int, default=3)
    parser.add_argument("--k", type=int, default=50)
    args = parser.parse_args()

    LoadPlugin(args.plugin, remote=False, ns=globals())
    LoadPlugin(PARAVIEW_FMM, remote=False, ns=globals())
    tmp = tempfile.mkdtemp()
    print("%-24s %7s %11s %11s %9s %11s %11s %9s %9s %8s" % (
        "mesh", "verts", "fmm_mean", "fmm_max", "fmm_ms", "svg_mean", "svg_max", "svg_ms",
        "build_s", "acc_x"))
    for path in args.meshes:
        ply = off_to_ply(path, tmp) if path.lower().endswith(".off") else path
        reader = PLYReader(FileNames=[ply])
        reader.UpdatePipeline()
        n = reader.GetDataInformation().GetNumberOfPoints()
        sources = [(k * 7919 + 13) % n for k in range(args.sources)]

        exact = SVGGeodesicDistance(Input=reader, Solver="Exact")
        svg = SVGGeodesicDistance(Input=reader, Solver="SVG (label-correcting)", K=args.k)
        seeds = ProgrammableFilter(Input=reader, Script=SEED_SCRIPT % sources[0])
        fmm = FastMarchingGeodesicDistanceFieldFromBinaryField(Input=seeds)
        fmm.SeedsNonZeroField = ["POINTS", "Seed"]

        # The first SVG execution builds the graph (once per mesh).
        svg.SourceVertexIds = [sources[0]]
        build = timed_update(svg)
        fmm_err, svg_err, fmm_t, svg_t = [], [], [], []
        for s in sources:
            exact.SourceVertexIds = [s]
            exact.UpdatePipeline()
            ref = fetch_array(exact, "GeodesicDistance")
            svg.SourceVertexIds = [s]
            svg_t.append(timed_update(svg))
            svg_err.append(errors(fetch_array(svg, "GeodesicDistance"), ref))
            seeds.Script = SEED_SCRIPT % s
            seeds.UpdatePipeline()
            fmm_t.append(timed_update(fmm))
            fmm_err.append(errors(fetch_array(fmm, "DistanceField"), ref))
        fm = np.mean([e[0] for e in fmm_err])
        sv = np.mean([e[0] for e in svg_err])
        print("%-24s %7d %11.2e %11.2e %9.1f %11.2e %11.2e %9.1f %9.2f %8.1f" % (
            os.path.basename(path), n, fm, np.max([e[1] for e in fmm_err]), 1e3 * np.mean(fmm_t), sv,
            np.max([e[1] for e in svg_err]), 1e3 * np.mean(svg_t), build, fm / sv))
        sys.stdout.flush()
        for proxy in (fmm, seeds, svg, exact, reader):
            Delete(proxy)
    print("fmm: ParaView's fast marching (GeodesicMeasurement plugin); svg: our SVG solver "
          "(label-correcting, K=%d), per solve once the graph is built (build_s: the build, "
          "once per mesh); errors are relative to our exact solver; acc_x = fmm_mean / svg_mean."
          % args.k)


if __name__ == "__main__":
    main()
