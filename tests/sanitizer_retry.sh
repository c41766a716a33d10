#!/usr/bin/env bash
# Runs one test executable of the sanitizer build (the CROSSCOMPILING_EMULATOR of tests/CMakeLists.txt).
# LeakSanitizer checks for leaks at exit by stopping the process's threads with a tracer; on this
# platform that tracer itself sometimes dies (SIGSEGV: "Tracer caught signal 11 ... LeakSanitizer has
# encountered a fatal error") after the test has passed, one run in several hundred. Such a run, and only
# such a run (no leak reported, no other sanitizer error), is run once more; any other failure stands.
out=$(mktemp) || exit 1
trap 'rm -f "$out"' EXIT
"$@" > "$out" 2>&1
rc=$?
cat "$out"
if [ "$rc" -ne 0 ] && grep -q "LeakSanitizer has encountered a fatal error" "$out" &&
   ! grep -q "ERROR: LeakSanitizer: detected memory leaks\|ERROR: AddressSanitizer\|runtime error:" "$out"; then
  echo "sanitizer_retry.sh: LeakSanitizer's tracer crashed (not a finding about the test); running it again"
  "$@"
  rc=$?
fi
exit "$rc"
