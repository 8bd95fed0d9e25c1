"""Hostile scripts and numbers through the Python API: long chains run, deep
nesting and runaway edits are one error with a line and column, bad numbers
are refused by the shared rules, and this Python process survives all of it."""
import random
import sys

from lvdif import vtkLVDIFEditor


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


random.seed(18)
ed = vtkLVDIFEditor()
ed.GlobalWarningDisplayOff()  # the refusals below are expected
if not ed.NewVolume(32, 32, 32, False):
    fail(ed.GetLastError())

# long chains and else-if chains: no recursion, the right value
n = 100000
terms = [random.randint(1, 9) for _ in range(n)]
if not ed.RunScript("x = " + "+".join(map(str, terms)) + "\nsphere 16 16 16 x % 5 + 3\n"):
    fail("chain: " + ed.GetLastError())
pick = random.randint(1, 29999)
src = f"k = {pick}\nif k == 0 {{ r = 1 }}" + "".join(f" else if k == {i} {{ r = {i % 7 + 2} }}" for i in range(1, 30000))
if not ed.RunScript(src + "\nsphere 8 8 8 r\n"):
    fail("else-if chain: " + ed.GetLastError())

# nesting past the limit: one error at line 1, this process alive
for name, text in [("parentheses", "x = " + "(" * n + "1" + ")" * n),
                   ("unary", "x = " + "-" * n + "1"),
                   ("calls", "x = " + "abs(" * n + "1" + ")" * n),
                   ("blocks", "if 1 {" * n)]:
    if ed.RunScript(text):
        fail(name + " ran")
    if "nested too deeply" not in ed.GetLastError() or ed.GetLastErrorLine() != 1 or ed.GetLastErrorColumn() < 1:
        fail(f"{name}: {ed.GetLastError()} at {ed.GetLastErrorLine()}:{ed.GetLastErrorColumn()}")

# runaway edits are refused before the work, with the line of the command
for spacing in (0.001, 0.002 + random.random() * 0.01):
    if ed.RunScript(f"spacing {spacing}\nline 1 1 1 {random.randint(10**5, 10**8)} 1 1\n"):
        fail("runaway line ran")
    if "more than the limit" not in ed.GetLastError() or ed.GetLastErrorLine() != 2:
        fail("runaway line: " + ed.GetLastError())

# numbers: the same rules as scripts and recordings
for bad in (1e300, float("inf"), float("nan"), -1.0, 2e7):
    before = ed.GetBlend()
    ed.SetBlend(bad)
    if ed.GetBlend() != before:
        fail(f"SetBlend({bad}) accepted")
    ed.SetSpacing(bad if bad != 2e7 else 1e-9)
    if ed.GetSpacing() != 1.6 and ed.GetSpacing() == bad:
        fail(f"SetSpacing({bad}) accepted")
    if ed.RunScript(f"blend {bad}\n".replace("inf", "1e400").replace("nan", "0/0")):
        fail(f"script blend {bad} ran")
if ed.Dab(1e300, 0, 0):
    fail("a dab at 1e300 was applied")
print("hostile scripts OK")
