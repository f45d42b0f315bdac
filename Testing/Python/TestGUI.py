"""ParaView GUI test (run as `paraview --script=TestGUI.py` under Xvfb, with PV_PLUGIN_PATH set
to the plugin's folder and GS_TEST_OUTPUT, GS_SOURCE_DIR in the environment).

- The plugin is loaded by the GUI at start-up and every filter is in the "Geodesic Shapes"
  menu category (the ShowInMenu hint of its proxy definition).
- The main job (Examples/main_job.py, the paper's Fig. 1 pipeline) runs inside the GUI
  and produces its screenshot and ParaView state.
The GUI has no Python exit: the script ends the process with os._exit(status) (0: passed);
results and failures are written to GS_TEST_OUTPUT/gui_result.txt.
"""
import os
import sys
import traceback

out = os.environ.get("GS_TEST_OUTPUT", ".")
source = os.environ.get("GS_SOURCE_DIR", ".")
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
    menus_ok = all(c == "Geodesic Shapes" for c in categories.values())

    output = os.path.join(out, "gui_main_job")
    sys.argv = ["main_job.py", "--output", output, "--check",
                "--plugin", os.environ.get("GS_PLUGIN_FILE", "")]
    globals_ = {"__file__": os.path.join(source, "Examples", "main_job.py"), "__name__": "__main__"}
    try:
        exec(open(globals_["__file__"]).read(), globals_)
        job_ok = True
    except SystemExit as e:
        job_ok = not e.code
        lines.append("main job exit: %r" % (e.code,))
    # (Names of this script may not survive the exec inside the GUI's shell: recompute.)
    import os
    picture = os.path.join(os.environ.get("GS_TEST_OUTPUT", "."), "gui_main_job", "main_job.png")
    job_ok = job_ok and os.path.exists(picture) and os.path.getsize(picture) > 0
    lines.append("main job in the GUI: %s" % ("ok" if job_ok else "FAILED"))
    status = 0 if menus_ok and job_ok else 1
except Exception:
    lines.append(traceback.format_exc())
finally:
    with open(os.path.join(out, "gui_result.txt"), "w") as f:
        f.write("\n".join(lines) + "\n" + ("passed\n" if status == 0 else "FAILED\n"))
    os._exit(status)
