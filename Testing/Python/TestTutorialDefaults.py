"""pvpython test: a new user's first pipeline typed with the defaults (issue: the DirectionArray
default left unresolved (no array name) when the inputs were not updated before the distributor
was made, and the run failed with 0 shapes).

Exactly as a user types it: no UpdatePipeline before making the distributor, no arrays set. The
distributor must place shapes, say which direction array it used (field data
DirectionArrayUsed: Cross Field's cell array Direction), and an input without any direction
must give a clear error and no shapes.

Usage: pvpython TestTutorialDefaults.py --plugin <GeodesicShapes.so> --data <Data dir>
"""
import os

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

import gs_test
from gs_test import check

args = gs_test.arguments(plugin=gs_test.REQUIRED, data=gs_test.REQUIRED)
LoadPlugin(args.plugin, remote=False, ns=globals())

mesh = PLYReader(FileNames=[os.path.join(args.data, "bumpy_sphere.ply")])
field = CrossField(Input=mesh)
field.Symmetry = 1
SetActiveSource(None)
tables = MSDTSource(ShapeFileNames=[os.path.join(args.data, "shapes", "star.png")])
shapes = ShapeDistributor(Input=field, Table=tables, ShapeSize=0.08)
print("DirectionArray as made:", list(shapes.DirectionArray))
# No array named "0" (a default of "0" repeated into the name, which the GUI showed as "0 (?)").
check(list(shapes.DirectionArray)[1] in ("", "Direction"),
      "DirectionArray as made names the array %r" % list(shapes.DirectionArray)[1])
shapes.UpdatePipeline()
placements = shapes.GetClientSideObject().GetOutputDataObject(0)
n = placements.GetNumberOfPoints()
used = placements.GetFieldData().GetAbstractArray("DirectionArrayUsed")
print("shapes:", n, "direction used:", used.GetValue(0) if used else None)
check(n > 100, "the tutorial as typed placed %d shapes" % n)
check(used is not None and used.GetValue(0) == "CELLS Direction",
      "DirectionArrayUsed is %s" % (used.GetValue(0) if used else None))

# The same in the order a GUI user clicks: the distributor made from the active source.
SetActiveSource(field)
shapes2 = ShapeDistributor(Table=tables, ShapeSize=0.08)
shapes2.UpdatePipeline()
n2 = shapes2.GetClientSideObject().GetOutputDataObject(0).GetNumberOfPoints()
check(n2 == n, "made from the active source: %d shapes, typed: %d" % (n2, n))

# The tutorial without SetActiveSource(None) and without ShapeSize: MSDT Source takes no input
# whatever is active, and the size is automatic (4% of the largest bounding-box side, stated in
# the field data ShapeSizeUsed), the value the GUI proposes.
SetActiveSource(field)
tables3 = MSDTSource(ShapeFileNames=[os.path.join(args.data, "shapes", "star.png")])
shapes3 = ShapeDistributor(Input=field, Table=tables3)
shapes3.UpdatePipeline()
placements3 = shapes3.GetClientSideObject().GetOutputDataObject(0)
n3 = placements3.GetNumberOfPoints()
size_used = placements3.GetFieldData().GetArray("ShapeSizeUsed")
bounds = mesh.GetDataInformation().GetBounds()
largest = max(bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4])
print("automatic size: %s (largest side %.4f), %d shapes"
      % (size_used.GetValue(0) if size_used else None, largest, n3))
check(size_used is not None and abs(size_used.GetValue(0) - 0.04 * largest) < 1e-9 * largest,
      "ShapeSizeUsed is not 4% of the largest side")
check(n3 > 100, "the tutorial without ShapeSize placed %d shapes" % n3)

# On inputs never updated (their bounds not known when the distributor is made), ShapeSize left
# unset or given as 0 stays 0 (automatic: 4% of the largest side), never a negative size.
for given in ({}, {"ShapeSize": 0.0}):
    fresh_mesh = PLYReader(FileNames=[os.path.join(args.data, "bumpy_sphere.ply")])
    fresh_field = CrossField(Input=fresh_mesh, Symmetry=1)
    fresh_tables = MSDTSource(ShapeFileNames=[os.path.join(args.data, "shapes", "star.png")])
    fresh = ShapeDistributor(Input=fresh_field, Table=fresh_tables, **given)
    check(fresh.ShapeSize == 0.0, "ShapeSize as made on a fresh input (%r): %r" % (given, fresh.ShapeSize))
    fresh.UpdatePipeline()
    placed = fresh.GetClientSideObject().GetOutputDataObject(0)
    used_size = placed.GetFieldData().GetArray("ShapeSizeUsed")
    check(placed.GetNumberOfPoints() == n3 and used_size is not None
          and abs(used_size.GetValue(0) - 0.04 * largest) < 1e-9 * largest,
          "automatic size on a fresh input (%r): %d shapes, size %s"
          % (given, placed.GetNumberOfPoints(), used_size.GetValue(0) if used_size else None))
    Delete(fresh)

# No direction anywhere: a clear error, no shapes.
plain = PLYReader(FileNames=[os.path.join(args.data, "bumpy_sphere.ply")])
bare = ShapeDistributor(Input=plain, Table=tables, ShapeSize=0.08)
bare.UpdatePipeline()
check(bare.GetClientSideObject().GetOutputDataObject(0).GetNumberOfPoints() == 0,
      "a mesh without directions gave shapes")

gs_test.finish()
