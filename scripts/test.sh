#!/usr/bin/env bash
# The whole test suite, as CI runs it: install the Debian packages, then
#  1. build and run every test optimised (preset release, GCC), and beside the tests
#  2. lint: clang-format and clang-tidy on the project's own sources (scripts/lint.sh);
#  3. build and run every test under AddressSanitizer + UndefinedBehaviorSanitizer (preset asan);
#  4. build the libFuzzer targets with clang and run each for 10 seconds (preset fuzz).
# Long checks carry the CTest label `slow` and are not run here (see docs/testing.md).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
jobs="$(nproc)"

cmake --preset release
cmake --build --preset release -j"$jobs"
# Lint beside the release tests: the tests leave a core idle much of the time (process starts,
# the serial tail of the longest tests), and lint needs only the configured build's database.
lint_log="$(mktemp)"
scripts/lint.sh build > "$lint_log" 2>&1 &
lint_pid=$!
tests_status=0
ctest --preset release -j"$jobs" || tests_status=$?
lint_status=0
wait "$lint_pid" || lint_status=$?
cat "$lint_log"
rm -f "$lint_log"
if [ "$tests_status" != 0 ] || [ "$lint_status" != 0 ]; then
  echo "test.sh: release tests exit $tests_status, lint exit $lint_status" >&2
  exit 1
fi

cmake --preset asan
cmake --build --preset asan -j"$jobs"
ctest --preset asan -j"$jobs"

cmake --preset fuzz
cmake --build --preset fuzz -j"$jobs"
ctest --preset fuzz  # one fuzzer at a time: each gets the whole machine for its 10 s
