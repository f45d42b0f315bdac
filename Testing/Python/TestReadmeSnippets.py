"""pvpython test: the README's pvpython snippets run as written.

Extracts every ```python block of README.md, in order, and runs them as one script from a
scratch folder that sees the repository's Data and the build's plugin where the README says
they are (Data/..., build/lib/...), so that what the snippets write lands there. Then the
distributor of the Shape Distributor snippet must have placed shapes.

Usage: pvpython TestReadmeSnippets.py --readme <README.md> --data <Data dir> --build <build dir>
"""
import argparse
import os
import re
import sys
import tempfile

parser = argparse.ArgumentParser()
parser.add_argument("--readme", required=True)
parser.add_argument("--data", required=True)
parser.add_argument("--build", required=True)
args = parser.parse_args()

with open(args.readme) as f:
    text = f.read()
blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
print("%d python snippet(s)" % len(blocks))
if len(blocks) < 2:
    sys.exit("expected the README's pvpython snippets")

scratch = tempfile.mkdtemp(prefix="readme-snippets-")
os.symlink(os.path.abspath(args.data), os.path.join(scratch, "Data"))
os.symlink(os.path.abspath(args.build), os.path.join(scratch, "build"))
os.chdir(scratch)
scope = {"__name__": "__readme__"}
for k, block in enumerate(blocks):
    print("--- snippet %d" % (k + 1))
    exec(compile(block, "README.md snippet %d" % (k + 1), "exec"), scope)

failures = []
shapes = scope.get("shapes")
if shapes is None:
    failures.append("the snippets define no 'shapes'")
else:
    shapes.UpdatePipeline()
    n = shapes.GetClientSideObject().GetOutputDataObject(0).GetNumberOfPoints()
    print("shapes placed by the README's Shape Distributor snippet:", n)
    if n == 0:
        failures.append("the README's Shape Distributor snippet placed no shape")
if not os.path.exists(os.path.join(scratch, "torus_distance.vtp")):
    failures.append("the first snippet's SaveData wrote nothing")
for f in failures:
    print("FAILED:", f)
sys.exit(1 if failures else 0)
