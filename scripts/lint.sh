#!/usr/bin/env bash
# Formatting and static analysis of the project's own sources (CI runs this from scripts/test.sh):
#  - clang-format --dry-run -Werror on every C++ file except generated/ (the generator's bytes,
#    checked by the staleness test instead);
#  - clang-tidy (.clang-tidy) on every project translation unit but the tests of a configured
#    build's compile_commands.json (default build/; configure it first, e.g. `cmake --preset release`).
# Usage: scripts/lint.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"

pick() { for tool in "$@"; do if command -v "$tool" > /dev/null; then echo "$tool"; return; fi; done; }
clang_format="$(pick clang-format-14 clang-format)"
clang_tidy="$(pick clang-tidy-14 clang-tidy)"
if [ -z "$clang_format" ] || [ -z "$clang_tidy" ]; then
  echo "lint: clang-format and clang-tidy are needed (scripts/install-deps.sh installs them)" >&2
  exit 1
fi

# The project's own C++ sources: tracked files when this is a git checkout, else every file.
if git rev-parse --is-inside-work-tree > /dev/null 2>&1; then
  mapfile -t sources < <(git ls-files '*.h' '*.hpp' '*.cpp' | grep -v '^generated/')
else
  mapfile -t sources < <(find apps bench examples frontend fuzz generator runtime support tests \
                           -name '*.h' -o -name '*.hpp' -o -name '*.cpp' | sort)
fi
echo "lint: clang-format on ${#sources[@]} files"
"$clang_format" --dry-run -Werror "${sources[@]}"

database="$build/compile_commands.json"
if [ ! -f "$database" ]; then
  echo "lint: $database is missing: configure the build first (cmake --preset release)" >&2
  exit 1
fi
# Translation units of the database that are project sources (not generated/ or the build tree),
# and not the tests (91 of 199 units, each parsing GoogleTest and often the emitted headers): they
# are compiled with -Werror and run under the sanitizers, and leaving them out keeps CI within its
# time; clang-tidy reviews the code that ships.
mapfile -t units < <(sed -n 's/^ *"file": "\(.*\)",\{0,1\}$/\1/p' "$database" | sort -u |
                       grep -F "$PWD/" | grep -v -e "^$PWD/generated/" -e "^$PWD/build" -e "^$PWD/tests/")
echo "lint: clang-tidy on ${#units[@]} translation units"
# GCC-only warning flags in the database are unknown to clang: not a finding.
printf '%s\n' "${units[@]}" |
  xargs -P "$(nproc)" -n 1 "$clang_tidy" -p "$build" --quiet --extra-arg=-Wno-unknown-warning-option
echo "lint: clean"
