"""ParaView GUI test (run as `paraview --script=TestGUI.py` under Xvfb, with PV_PLUGIN_PATH set
to the plugin's folder and GS_TEST_OUTPUT, GS_SOURCE_DIR in the environment).

- The plugin is loaded by the GUI at start-up and every filter is in the "Geodesic Shapes"
  menu category (the ShowInMenu hint of its proxy definition).
- The main job (Examples/main_job.py, the paper's Fig. 1 pipeline) runs inside the GUI
  and produces its screenshot and ParaView state.
The checks are gs_test's; the GUI has no Python exit, so the script ends the process with
os._exit(status), the status gs_test.finish() gives (0: passed). Results and failures are written
to GS_TEST_OUTPUT/gui_result.txt.
"""
import os
import sys
import traceback

out = os.environ.get("GS_TEST_OUTPUT", ".")
source = os.environ.get("GS_SOURCE_DIR", ".")
# The GUI runs the script without its folder on the module path (and without __file__).
sys.path.insert(0, os.path.join(source, "Testing", "Python"))
import gs_test  # noqa: E402
from gs_test import check  # noqa: E402

os.makedirs(out, exist_ok=True)
status = 1
lines = []
try:
    from paraview.simple import *  # noqa: F401,F403
    from paraview import servermanager

    pdm = servermanager.vtkSMProxyManager.GetProxyManager().GetActiveSessionProxyManager() \
        .GetProxyDefinitionManager()
    categories = {}
    for group, name in (("filters", "ShapeDistributor"), ("filters", "CrossField"),
                        ("filters", "SVGGeodesicDistance"), ("filters", "GeodesicPolarCoordinates"),
                        ("sources", "MSDTSource")):
        xml = pdm.GetCollapsedProxyDefinition(group, name, None, True)
        category = None
        if xml:
            hints = xml.FindNestedElementByName("Hints")
            menu = hints.FindNestedElementByName("ShowInMenu") if hints else None
            category = menu.GetAttribute("category") if menu else None
        categories[name] = category
    lines.append("menu categories: %r" % categories)
    elsewhere = {n: c for n, c in categories.items() if c != "Geodesic Shapes"}
    check(not elsewhere, "not in the 'Geodesic Shapes' menu category: %r" % elsewhere)

    output = os.path.join(out, "gui_main_job")
    sys.argv = ["main_job.py", "--output", output, "--check",
                "--plugin", os.environ.get("GS_PLUGIN_FILE", "")]
    globals_ = {"__file__": os.path.join(source, "Examples", "main_job.py"), "__name__": "__main__"}
    exit_code = None
    try:
        exec(open(globals_["__file__"]).read(), globals_)
    except SystemExit as e:
        exit_code = e.code
        lines.append("main job exit: %r" % (e.code,))
    # (Names of this script may not survive the exec inside the GUI's shell: recompute.)
    import os
    import gs_test
    picture = os.path.join(os.environ.get("GS_TEST_OUTPUT", "."), "gui_main_job", "main_job.png")
    has_picture = os.path.exists(picture) and os.path.getsize(picture) > 0
    job_ok = not exit_code and has_picture
    lines.append("main job in the GUI: %s" % ("ok" if job_ok else "FAILED"))
    gs_test.check(not exit_code, "the main job in the GUI exited with %r" % (exit_code,))
    gs_test.check(has_picture, "the main job in the GUI wrote no picture %s" % picture)
except Exception:
    lines.append(traceback.format_exc())
    gs_test.check(False, "the test raised %s" % traceback.format_exc().strip().splitlines()[-1])
finally:
    try:
        gs_test.finish("passed")
        status = 0
    except SystemExit as e:  # finish() after a failed check
        status = e.code
    lines += ["FAILED: %s" % message for message in gs_test.failures]
    with open(os.path.join(out, "gui_result.txt"), "w") as f:
        f.write("\n".join(lines) + "\n" + ("passed\n" if status == 0 else "FAILED\n"))
    os._exit(status)
