# Sourced by the editor's shell tests once they have read their arguments:
# a fresh folder $DIR, and `fail MESSAGE`: one FAIL line, the test's own
# on_fail (where it defines one: a process to stop), then status 1.
rm -rf "$DIR"
mkdir -p "$DIR"
fail() {
  echo "FAIL: $*"
  if declare -F on_fail > /dev/null; then on_fail; fi
  exit 1
}
