"""Which geodesic engine answers first: every engine of SVG Geodesic Distance, ParaView's fast
marching and CGAL's heat method, on the same meshes and sources, in one run.

For each mesh (a file, or `file:S` for the file subdivided S times at edge midpoints by
ParaView's linear subdivision) and each engine:
  first   the first Apply as a user runs it: a new filter on the mesh, one source (our filters:
          mesh conversion, graph build for the graph solvers, solve; CGAL: the factorization
          and the first solve, from HeatMethodComparison on the same mesh and sources);
  next    the median time of a further source on the same filter (the graph, the converted mesh
          or the factorization reused);
  mean / max  relative error against our exact solver over every other vertex.
Each engine runs once per mesh, so a graph solver's first Apply builds its graph.

    xvfb-run -a pvpython Benchmarks/geodesic_engines.py --plugin build/lib/.../GeodesicShapes.so \\
        --heat build/bin/HeatMethodComparison mesh.ply mesh.off:2 ... [--sources 3]
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile
import time

import numpy as np
from paraview import servermanager as sm
from paraview.simple import *  # noqa: F401,F403
from vtkmodules.numpy_interface import dataset_adapter as dsa

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from compare_paraview_fmm import PARAVIEW_FMM, SEED_SCRIPT, errors, fetch_array, off_to_ply  # noqa: E402

ENGINES = [
    ("Virtual sources (no precompute)", {}),
    ("DGG (accuracy-bounded)", {"GraphAccuracy": 0.1}),
    ("SVG (label-correcting)", {"K": 50}),
    ("Exact", {}),
]


def timed_update(proxy):
    start = time.perf_counter()
    proxy.UpdatePipeline()
    return time.perf_counter() - start


def mesh_file(spec, folder):
    """The mesh as a binary PLY (ParaView has no OFF reader), subdivided when asked."""
    path, _, levels = spec.partition(":")
    ply = off_to_ply(path, folder) if path.lower().endswith(".off") else path
    levels = int(levels or 0)
    if levels == 0:
        return ply
    reader = PLYReader(FileNames=[ply])
    subdivided = Subdivide(Input=reader, NumberofSubdivisions=levels)  # linear, at edge midpoints
    out = os.path.join(folder, "%s_x%d.ply" % (os.path.basename(path), levels))
    SaveData(out, proxy=subdivided, FileType="Binary")
    Delete(subdivided)
    Delete(reader)
    return out


def heat_method(program, ply, sources):
    """CGAL's heat method (direct, prefactored) from HeatMethodComparison on the same file."""
    out = subprocess.run([program, ply, "--heat-only", "--sources", str(sources), "--rounds", "1"],
                         capture_output=True, text=True, check=True).stdout
    m = re.search(r"CGAL heat method \(direct\): setup ([0-9.]+) s, solve ([0-9.]+) ms.*?"
                  r"mean error ([-+0-9.eainf]+), max ([-+0-9.eainf]+)", out)
    setup, solve, mean, worst = (float(x) for x in m.groups())
    return setup, solve / 1e3, mean, worst


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("meshes", nargs="+")
    parser.add_argument("--plugin", required=True, help="path to GeodesicShapes.so")
    parser.add_argument("--heat", help="path to HeatMethodComparison (CGAL's heat method)")
    parser.add_argument("--sources", type=int, default=3)
    parser.add_argument("--no-fmm", action="store_true", help="skip ParaView's fast marching")
    args = parser.parse_args()

    LoadPlugin(args.plugin, remote=False, ns=globals())
    if not args.no_fmm:
        LoadPlugin(PARAVIEW_FMM, remote=False, ns=globals())
    tmp = tempfile.mkdtemp()
    print("| mesh | faces | engine | first answer | next source | mean error | max error |")
    print("|---|---|---|---|---|---|---|")
    for spec in args.meshes:
        ply = mesh_file(spec, tmp)
        reader = PLYReader(FileNames=[ply])
        reader.UpdatePipeline()
        info = reader.GetDataInformation()
        n, faces = info.GetNumberOfPoints(), info.GetNumberOfCells()
        sources = [(k * 7919 + 13) % n for k in range(args.sources)]
        name = os.path.basename(spec)

        def row(engine, first, nxt, mean, worst):
            print("| %s | %d | %s | %.3f s | %.4f s | %.2e | %.2e |" % (
                name, faces, engine, first, nxt, mean, worst))
            sys.stdout.flush()

        reference = {}
        for engine, properties in reversed(ENGINES):  # Exact first: the reference
            f = SVGGeodesicDistance(Input=reader, Solver=engine, **properties)
            firsts, nexts, errs = None, [], []
            for i, s in enumerate(sources):
                f.SourceVertexIds = [s]
                t = timed_update(f)
                d = fetch_array(f, "GeodesicDistance")
                if engine == "Exact":
                    reference[s] = d
                if i == 0:
                    firsts = t
                else:
                    nexts.append(t)
                errs.append(errors(d, reference[s]) if engine != "Exact" else (0.0, 0.0))
            row(engine + (" %s" % properties if properties else ""), firsts,
                float(np.median(nexts)) if nexts else float("nan"),
                np.mean([e[0] for e in errs]), np.max([e[1] for e in errs]))
            Delete(f)
        if not args.no_fmm:
            seeds = ProgrammableFilter(Input=reader, Script=SEED_SCRIPT % sources[0])
            fmm = FastMarchingGeodesicDistanceFieldFromBinaryField(Input=seeds)
            fmm.SeedsNonZeroField = ["POINTS", "Seed"]
            times, errs = [], []
            for s in sources:
                seeds.Script = SEED_SCRIPT % s
                times.append(timed_update(fmm))
                errs.append(errors(fetch_array(fmm, "DistanceField"), reference[s]))
            row("ParaView fast marching", times[0], float(np.median(times[1:])) if len(times) > 1 else float("nan"),
                np.mean([e[0] for e in errs]), np.max([e[1] for e in errs]))
            Delete(fmm)
            Delete(seeds)
        if args.heat:
            setup, solve, mean, worst = heat_method(args.heat, ply, args.sources)
            row("CGAL heat method (direct, prefactored)", setup, solve, mean, worst)
        Delete(reader)
    print("first answer: the first Apply of a new filter (mesh conversion, any graph build or "
          "factorization, one solve); next source: the median further solve; errors relative to "
          "the exact solver over every vertex.")


if __name__ == "__main__":
    main()
