"""Plain python3 test: the README's numpy snippet (its ```python numpy block) runs as written.

Runs every ```python numpy block of README.md, in order, from a scratch folder that sees the
repository's Data where the README says it is; the package comes from PYTHONPATH, as the README
says. Then the distribution must hold shapes of both classes (the image and the polygon: their
sizes comparable, as the snippet's comment promises).

Usage: python3 TestReadmeNumpy.py --readme <README.md> --data <Data dir>
"""
import os
import re
import tempfile

import gs_test
from gs_test import check

args = gs_test.arguments(readme=gs_test.REQUIRED, data=gs_test.REQUIRED)

text = open(args.readme).read()
blocks = re.findall(r"```python numpy\n(.*?)```", text, flags=re.S)
print("%d numpy snippet(s)" % len(blocks))
check(blocks, "no ```python numpy block in the README")
if not blocks:
    gs_test.finish()  # nothing to run
scratch = tempfile.mkdtemp(prefix="readme-numpy-")
os.symlink(os.path.abspath(args.data), os.path.join(scratch, "Data"))
os.chdir(scratch)
scope = {"__name__": "__readme__"}
for k, block in enumerate(blocks):
    exec(compile(block, "README.md numpy snippet %d" % (k + 1), "exec"), scope)

placed = scope.get("placed")
import numpy  # noqa: E402

classes = numpy.bincount(numpy.asarray(placed.class_ids), minlength=2) if placed is not None else None
print("shapes per class:", classes)
check(placed is not None and len(placed.positions) >= 50 and classes is not None
      and min(classes[:2]) >= 10,
      "the snippet placed %s shape(s), per class %s (expected at least 50, and 10 of each class)"
      % (None if placed is None else len(placed.positions), classes))
gs_test.finish()
