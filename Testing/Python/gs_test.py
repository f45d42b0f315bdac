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
