"""What every pvpython test of the project shares: its command-line arguments, its checks and its
verdict (the tests run as scripts; their folder is on the module path).

    args = gs_test.arguments(plugin=gs_test.REQUIRED, data=gs_test.REQUIRED, temp=".")
    check(condition, "what failed")   # from gs_test import check
    gs_test.finish()                   # exit 1 after any failed check, else print the verdict
"""
import argparse
import os
import sys

REQUIRED = object()
failures = []


def arguments(**options):
    """Parses --name options (underscores in a name are dashes on the command line): REQUIRED
    or a default value for each."""
    parser = argparse.ArgumentParser()
    for name, default in options.items():
        flag = "--" + name.replace("_", "-")
        if default is REQUIRED:
            parser.add_argument(flag, required=True)
        else:
            parser.add_argument(flag, default=default)
    return parser.parse_args()


def check(condition, message):
    """Records and prints a failure when `condition` is false; the test goes on."""
    if not condition:
        failures.append(message)
        print("FAILED:", message)


def finish(verdict="OK"):
    """Exits with status 1 after any failed check, else prints `verdict`."""
    if failures:
        print("%d failure(s)" % len(failures))
        sys.exit(1)
    print(verdict)


def mpi_env():
    """The environment of an mpiexec child of a test: pvpython initialised MPI as a singleton,
    and its OpenMPI/PMIx variables would make the children believe they are part of its job."""
    env = {k: v for k, v in os.environ.items()
           if not k.startswith(("OMPI_", "PMIX_", "ORTE_", "OPAL_"))}
    env["OMPI_ALLOW_RUN_AS_ROOT"] = "1"
    env["OMPI_ALLOW_RUN_AS_ROOT_CONFIRM"] = "1"
    env["OMPI_MCA_rmaps_base_oversubscribe"] = "1"
    # A process that waits for another yields its core instead of polling.
    env["OMPI_MCA_mpi_yield_when_idle"] = "1"
    return env


def run_checked(command, label, env, timeout=600):
    """Runs a sub-run (pvbatch, mpiexec, a pvpython client), prints its time and checks that it
    succeeded without ParaView errors; a failed run ends the test (what follows needs its
    outputs)."""
    import subprocess
    import time
    start = time.time()
    result = subprocess.run(command, env=env, timeout=timeout, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, universal_newlines=True)
    print("%s: %.1f s" % (label, time.time() - start))
    passed = result.returncode == 0 and "ERR|" not in result.stdout
    if not passed:
        print(result.stdout)
    check(passed, "%s failed (exit %d%s)" % (label, result.returncode,
                                            ", ParaView errors" if "ERR|" in result.stdout else ""))
    if not passed:
        finish()


class PVServer:
    """`with PVServer(mpiexec, pvserver, processes, env) as port:` a P-process pvserver on a free
    local port, stopped on leaving; the test ends if it does not start."""

    def __init__(self, mpiexec, pvserver, processes, env):
        self.command = [mpiexec, "-n", str(processes), pvserver]
        self.env = env
        self.server = None

    def __enter__(self):
        import socket
        import subprocess
        import time
        s = socket.socket()
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
        s.close()
        self.server = subprocess.Popen(self.command + ["--server-port=%d" % port], env=self.env,
                                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                       universal_newlines=True)
        deadline = time.time() + 120
        ready = False
        while time.time() < deadline:
            line = self.server.stdout.readline()
            if not line:
                break
            if "Accepting connection" in line:
                ready = True
                break
        check(ready, "pvserver did not start")
        if not ready:
            self.__exit__(None, None, None)
            finish()  # no server to connect to
        return port

    def __exit__(self, *exc):
        import subprocess
        self.server.terminate()
        try:
            self.server.wait(timeout=30)
        except subprocess.TimeoutExpired:
            self.server.kill()
        return False


def connect_run(connect, plugin, ns):
    """The start of a sub-run: connected to a pvserver (`connect` = host:port) or in pvbatch,
    with the plugin loaded into `ns`; returns this process's rank (0 on a client)."""
    from paraview.simple import Connect, LoadPlugin
    import vtk
    rank = 0
    if connect:
        host, port = connect.split(":")
        Connect(host, int(port))
        LoadPlugin(plugin, remote=True, ns=ns)
    else:
        rank = vtk.vtkMultiProcessController.GetGlobalController().GetLocalProcessId()
    LoadPlugin(plugin, remote=False, ns=ns)
    return rank


def write_polydata(data, path):
    """A vtkPolyData as .vtp, inline base64 (Debian's expat rejects raw appended data)."""
    import vtk
    writer = vtk.vtkXMLPolyDataWriter()
    writer.SetDataModeToBinary()
    writer.SetFileName(path)
    writer.SetInputData(data)
    writer.Write()


def read_polydata(path):
    import vtk
    reader = vtk.vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()
