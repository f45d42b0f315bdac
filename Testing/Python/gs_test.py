"""What every pvpython test of the project shares: its command-line arguments, its checks and its
verdict (the tests run as scripts; their folder is on the module path).

    args = gs_test.arguments(plugin=gs_test.REQUIRED, data=gs_test.REQUIRED, temp=".")
    check(condition, "what failed")   # from gs_test import check
    gs_test.finish()                   # exit 1 after any failed check, else print the verdict
"""
import argparse
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
