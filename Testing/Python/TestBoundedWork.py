"""pvpython test: Shape Distributor runs that once ran away end in an error before any work, or
run bounded and stop soon after an abort.

On the bundled torus (about 2.8 wide, area 15.75) with the bundled star and fish (a long class):
- shapes larger than the surface (ShapeSize 3 and 50, a density factor of 1e6 everywhere): an
  error naming ShapeSize, no shapes, in well under the time a single candidate used to take;
- shapes so small that the run would exceed the available memory (ShapeSize 3e-3 against
  GS_AVAILABLE_MEMORY = 2 GB) or absurdly small (1e-310): an error, no overflowing count;
- a run that places nothing (ShapeSize 1.4, the star alone: its maps fold round the tube) counts
  the candidates each check rejected (field data) and warns, naming FaithfulCheck;
- long runs aborted at 1 s: ShapeSize 1.4 (wider than the tube, smaller than the surface: every
  candidate fails the drawn checks until MaximalFailures, about 100 s) and 0.01 (minutes of
  shapes): empty outputs, returned within 2 s of the request (the distributor polls the abort
  inside its rounds every 0.1 s).

Usage: pvpython TestBoundedWork.py --plugin <GeodesicShapes.so> --data <Data dir>
"""
import os
import time

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from vtkmodules.vtkCommonCore import vtkCommand

import gs_test
from gs_test import check

args = gs_test.arguments(plugin=gs_test.REQUIRED, data=gs_test.REQUIRED)
LoadPlugin(args.plugin, remote=False, ns=globals())

tables = MSDTSource(ShapeFileNames=[os.path.join(args.data, "shapes", name) for name in ("star.png", "fish.png")])
mesh = PLYReader(FileNames=[os.path.join(args.data, "torus.ply")])
field = CrossField(Input=mesh, Symmetry=1)
field.UpdatePipeline()
dense = Calculator(Input=field, ResultArrayName="f", Function="1e6")


def run(size, density=False, abort_at=None):
    shapes = ShapeDistributor(Input=dense if density else field, Table=tables, ShapeSize=size, Seed=3)
    shapes.DirectionArray = ["CELLS", "Direction"]
    shapes.DensityArray = ["POINTS", "f" if density else "None"]
    algorithm = shapes.GetClientSideObject()
    asked = []
    start = time.time()

    def on_progress(caller, event):
        if abort_at is not None and not asked and time.time() - start > abort_at:
            asked.append(time.time())
            caller.SetAbortExecute(1)
    algorithm.AddObserver(vtkCommand.ProgressEvent, on_progress)
    shapes.UpdatePipeline()
    end = time.time()
    placed = algorithm.GetOutputDataObject(0).GetNumberOfPoints()
    Delete(shapes)
    return placed, end - start, (end - asked[0]) if asked else None


# (The error text itself is checked by the filters' C++ input tests; here: no shapes, quickly.)
for size, density in ((3.0, False), (50.0, False), (0.112, True), (1e-310, False)):
    placed, seconds, _ = run(size, density)
    print("ShapeSize %g%s: %d shapes in %.2f s" % (size, " x density 1e6" if density else "", placed, seconds))
    check(placed == 0 and seconds < 20, "ShapeSize %g%s: %d shapes in %.1f s"
          % (size, " x 1e6" if density else "", placed, seconds))

os.environ["GS_AVAILABLE_MEMORY"] = "2e9"
placed, seconds, _ = run(3e-3)
del os.environ["GS_AVAILABLE_MEMORY"]
print("ShapeSize 3e-3 with 2 GB available: %d shapes in %.2f s" % (placed, seconds))
check(placed == 0 and seconds < 20, "ShapeSize 3e-3 was not refused (%d shapes, %.1f s)" % (placed, seconds))

# A run that places nothing says why: the counts of candidates by the check that rejected them
# (field data), and a warning naming the check. ShapeSize 1.4 with the star alone: wider than
# the tube, every candidate's map folds (FaithfulCheck); one round of 256 candidates.
from vtkmodules.util.misc import calldata_type  # noqa: E402
from vtkmodules.vtkCommonCore import VTK_STRING  # noqa: E402
star = MSDTSource(ShapeFileNames=[os.path.join(args.data, "shapes", "star.png")])
folded = ShapeDistributor(Input=field, Table=star, ShapeSize=1.4, Seed=3, MaximalFailures=1)
folded.DirectionArray = ["CELLS", "Direction"]
warned = []


@calldata_type(VTK_STRING)
def on_warning(caller, event, text):
    warned.append(text)


folded.GetClientSideObject().AddObserver(vtkCommand.WarningEvent, on_warning)
folded.UpdatePipeline()
data = folded.GetClientSideObject().GetOutputDataObject(0)
counts = {name: data.GetFieldData().GetArray(name).GetValue(0) for name in (
    "NumberOfCandidates", "CandidatesWithoutShape", "CandidatesRejectedByTables",
    "CandidatesRejectedByFaithfulCheck", "CandidatesRejectedByDrawnCheck")}
print("ShapeSize 1.4, star: %d shapes, %s" % (data.GetNumberOfPoints(), counts))
rejected = sum(v for k, v in counts.items() if k != "NumberOfCandidates")
check(counts["NumberOfCandidates"] >= 256 and
      rejected + data.GetNumberOfPoints() == counts["NumberOfCandidates"] and
      counts["CandidatesRejectedByFaithfulCheck"] > 0.9 * counts["NumberOfCandidates"],
      "rejection counts: %s" % counts)
check(any("FaithfulCheck rejected" in w and "ShapeSize" in w for w in warned),
      "no warning naming FaithfulCheck: %s" % warned)
Delete(folded)

for size in (1.4, 0.01):
    placed, seconds, latency = run(size, abort_at=1.0)
    print("ShapeSize %g aborted at 1 s: returned %.2f s after the request (%d shapes)"
          % (size, latency if latency is not None else -1, placed))
    check(latency is not None and latency < 2.0 and placed == 0,
          "abort at ShapeSize %g: latency %s s, %d shapes" % (size, latency, placed))

gs_test.finish()
