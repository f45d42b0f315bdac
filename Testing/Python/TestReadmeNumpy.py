"""Plain python3 test: the README's numpy snippet (its ```python numpy block) runs as written.

Runs every ```python numpy block of README.md, in order, from a scratch folder that sees the
repository's Data where the README says it is; the package comes from PYTHONPATH, as the README
says. Then the distribution must hold shapes of both classes (the image and the polygon: their
sizes comparable, as the snippet's comment promises).

Usage: python3 TestReadmeNumpy.py --readme <README.md> --data <Data dir>
"""
import argparse
import os
import re
import sys
import tempfile

parser = argparse.ArgumentParser()
parser.add_argument("--readme", required=True)
parser.add_argument("--data", required=True)
args = parser.parse_args()

text = open(args.readme).read()
blocks = re.findall(r"```python numpy\n(.*?)```", text, flags=re.S)
print("%d numpy snippet(s)" % len(blocks))
if not blocks:
    sys.exit("FAILED: no ```python numpy block in the README")
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
if placed is None or len(placed.positions) < 50 or classes is None or min(classes[:2]) < 10:
    print("FAILED: the snippet placed %s" % (classes,))
    sys.exit(1)
print("OK")
