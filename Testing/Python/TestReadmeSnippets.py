"""pvpython test: the README's pvpython snippets run as written.

Extracts every ```python block of README.md, in order, and runs them as one script from a
scratch folder that sees the repository's Data and the build's plugin where the README says
they are (Data/..., build/lib/...), so that what the snippets write lands there. Then the
distributor of the Shape Distributor snippet must have placed shapes.

Usage: pvpython TestReadmeSnippets.py --readme <README.md> --data <Data dir> --build <build dir>
"""
import os
import re
import tempfile

import gs_test
from gs_test import check

args = gs_test.arguments(readme=gs_test.REQUIRED, data=gs_test.REQUIRED, build=gs_test.REQUIRED)

with open(args.readme) as f:
    text = f.read()
blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
print("%d python snippet(s)" % len(blocks))
check(len(blocks) >= 2, "expected the README's pvpython snippets (at least 2 ```python blocks)")
if len(blocks) < 2:
    gs_test.finish()  # nothing to run

scratch = tempfile.mkdtemp(prefix="readme-snippets-")
os.symlink(os.path.abspath(args.data), os.path.join(scratch, "Data"))
os.symlink(os.path.abspath(args.build), os.path.join(scratch, "build"))
os.chdir(scratch)
scope = {"__name__": "__readme__"}
for k, block in enumerate(blocks):
    print("--- snippet %d" % (k + 1))
    exec(compile(block, "README.md snippet %d" % (k + 1), "exec"), scope)

shapes = scope.get("shapes")
check(shapes is not None, "the snippets define no 'shapes'")
if shapes is not None:
    shapes.UpdatePipeline()
    n = shapes.GetClientSideObject().GetOutputDataObject(0).GetNumberOfPoints()
    print("shapes placed by the README's Shape Distributor snippet:", n)
    check(n != 0, "the README's Shape Distributor snippet placed no shape")
check(os.path.exists(os.path.join(scratch, "torus_distance.vtp")),
      "the first snippet's SaveData wrote nothing")
gs_test.finish()
