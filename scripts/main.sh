#!/usr/bin/env bash
# The main job on built-in defaults: install the Debian packages, build (Release), then derive
# M12, M8 and M7 and print the paper's Table 1 beside the derived values.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)" --target boxgen
./build/apps/boxgen table1
