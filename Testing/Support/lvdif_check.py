"""The one check helper of the Python tests (Debian's python3 with the system
VTK) and the ParaView plugin's pvpython / pvbatch tests. Both test definitions
put Testing/Support on PYTHONPATH (Testing/Python/CMakeLists.txt,
Apps/ParaViewPlugin/Testing/CMakeLists.txt): `from lvdif_check import check, finish`.
"""
import sys


def check(ok, what):
    """Prints `ok   WHAT` or `FAIL WHAT` (the tests' FAIL_REGULAR_EXPRESSION
    matches "FAIL ") and counts a failure in check.failures; returns ok."""
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        check.failures += 1
    return bool(ok)


check.failures = 0


def finish():
    """Ends a test: prints the number of failed checks and exits 1 if any failed."""
    print("%d failed checks" % check.failures, flush=True)
    sys.exit(1 if check.failures else 0)
