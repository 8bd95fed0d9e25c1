"""Bad command lines get one clear line on stderr and a non-zero exit code."""
import subprocess
import sys

exe, out = sys.argv[1], sys.argv[2]


def run(*args):
    r = subprocess.run([exe, *args], capture_output=True, text=True, timeout=60)
    return r.returncode, r.stderr.strip()


code, err = run("no-such-command")
assert code == 2 and "unknown command" in err, (code, err)
code, err = run("demo", "--bogus", "1")
assert code == 1 and err == "lvdif demo: unknown option --bogus", (code, err)
code, err = run("demo", "--size", "ten")
assert code == 1 and "expects an integer" in err, (code, err)
code, err = run("demo", "--size", "100000000", "--out", out)
assert code == 1 and ("out of range" in err or "limit" in err), (code, err)
print("error handling OK")
