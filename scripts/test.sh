#!/usr/bin/env bash
# Builds virtual_go and runs every test (gtest on the core, rostest on the node and tools).
# Prints a final line "N passed, M failed"; exits non-zero when anything failed, when a test
# binary could not be built, or when no test ran.
set -uo pipefail
case "${1:-}" in
  -h | --help)
    echo "usage: scripts/test.sh   set up (packages, build), run all tests, print 'N passed, M failed'"
    exit 0
    ;;
esac

source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"

fail() {
  echo "virtual_go tests: $*" >&2
  echo "0 passed, 1 failed"
  exit 1
}

vg_setup || fail "set-up or build failed"
cmake --build "$VG_BUILD" --target tests -- -j"$(nproc)" || fail "a test binary could not be built"

rm -rf "$VG_BUILD/test_results"
# Sequential: rostests each start a master; the counter below reads every result file.
(
  vg_source_devel || exit 1
  cmake --build "$VG_BUILD" --target run_tests -- -j1
) 2>&1 | tee "$VG_BUILD/run_tests.log" | grep -E "^\[ *(RUN|OK|FAILED|PASSED) |FAILURE|ERROR|Ran |^SUMMARY|^ \* RESULT" || true

/usr/bin/python3 "$VG_ROOT/scripts/count_test_results.py" "$VG_BUILD/test_results"
