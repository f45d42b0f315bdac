"""Plain python3 test: ParaView's help shows a page of its own for every filter and source of the
plugin.

ParaView's help generator (paraview_add_plugin's XML documentation) renders each proxy's
Documentation into one HTML page; an unbalanced bracket or parenthesis in one proxy's text once
made it swallow every later proxy into that page (their "?" then opened the generic front page).
This test reads the server-manager XMLs and the generated help (.qhp and HTML): every proxy
must have its own page, holding its own title and no other proxy's; every Documentation text
must balance its brackets and parentheses (the cause, named with its file and line).

Usage: python3 TestHelpPages.py --xml <Filters dir> --help-dir <paraview_help dir>
"""
import glob
import os
import re

import gs_test
from gs_test import check

args = gs_test.arguments(xml=gs_test.REQUIRED, help_dir=gs_test.REQUIRED)

# A repeatable property without a file list (ParaView's value list widget) shows no label of
# its own: it must sit alone in a labelled PropertyGroup, whose label names it (Class Weights
# was an unlabelled empty box).
for path in sorted(glob.glob(os.path.join(args.xml, "*.xml"))):
    text = open(path, encoding="utf-8").read()
    for proxy in re.finditer(r"<SourceProxy(.*?)</SourceProxy>", text, re.S):
        body = proxy.group(1)
        groups = [(g.group(1), re.findall(r'<Property name="(\w+)"', g.group(2)))
                  for g in re.finditer(r'<PropertyGroup label="([^"]*)">(.*?)</PropertyGroup>', body, re.S)]
        for prop in re.finditer(r'<(\w+VectorProperty) name="(\w+)"([^>]*)>(.*?)</\1>', body, re.S):
            if 'repeat_command="1"' not in prop.group(3) or "FileListDomain" in prop.group(4):
                continue
            name = prop.group(2)
            alone = [label for label, members in groups if members == [name] and label.strip()]
            check(alone, "%s: the list property %s is not alone in a labelled PropertyGroup (its "
                  "widget would show no label)" % (os.path.basename(path), name))

proxies = []  # (group, name, label)
for path in sorted(glob.glob(os.path.join(args.xml, "*.xml"))):
    text = open(path, encoding="utf-8").read()
    for group in re.finditer(r'<ProxyGroup name="(\w+)">(.*?)</ProxyGroup>', text, re.S):
        for proxy in re.finditer(r'<SourceProxy name="(\w+)"(.*?)>', group.group(2), re.S):
            label = re.search(r'label="([^"]+)"', proxy.group(2))
            proxies.append((group.group(1), proxy.group(1), label.group(1) if label else proxy.group(1)))
    for doc in re.finditer(r"<Documentation[^>]*>(.*?)</Documentation>", text, re.S):
        body = doc.group(1)
        line = text[: doc.start()].count("\n") + 1
        for opening, closing in (("[", "]"), ("(", ")")):
            check(body.count(opening) == body.count(closing),
                  "%s:%d: Documentation has %d '%s' and %d '%s' (ParaView's help generator merges "
                  "the proxies after it into one page)" % (os.path.basename(path), line, body.count(opening),
                                                          opening, body.count(closing), closing))

print("proxies:", ", ".join("%s.%s" % (g, n) for g, n, _ in proxies))
check(len(proxies) >= 6, "only %d proxies found in the XMLs" % len(proxies))
qhp = open(os.path.join(args.help_dir, "GeodesicShapes.qhp"), encoding="utf-8").read()
files = set(re.findall(r"<file>([^<]+)</file>", qhp))
for group, name, label in proxies:
    page = "%s.%s.html" % (group, name)
    check(page in files, "no help page %s for %s (%s)" % (page, label, name))
    path = os.path.join(args.help_dir, page)
    if not os.path.exists(path):
        check(False, "%s missing from the help folder" % page)
        continue
    html = open(path, encoding="utf-8").read()
    titles = re.findall(r"<h2>([^<(]+)\((\w+)\)", html)
    check([t[1] for t in titles] == [name], "%s holds the titles %s, not %s's alone" % (page, titles, name))
    check(len(html) > 1500, "%s is nearly empty (%d bytes)" % (page, len(html)))

gs_test.finish("OK: %d proxies, each with its own help page" % len(proxies))
