#!/usr/bin/env bash
# The GL device's checks on a machine with a GPU (docs/gpu.md "The GL device"): the renderer EGL
# gives, the gl-label tests on it, and `boxrecon bench --device gl --json` (the issue's targets:
# M7 float evaluations per second and over the fetch floor, ms per 1024 x 1024 render). Builds
# nothing: BUILD_DIR is a release build made elsewhere (its binaries and their shared libraries
# carried over; the machine brings its own GL driver and EGL vendor files). Under 4 minutes.
#
#   scripts/gpu_check.sh BUILD_DIR [OUT_DIR]
#
# OUT_DIR (default ./gpu_check) receives renderer.txt, gl_tests.txt and bench.json.
set -uo pipefail

build=${1:?usage: scripts/gpu_check.sh BUILD_DIR [OUT_DIR]}
out=${2:-gpu_check}
boxrecon=$build/apps/boxrecon
gl_tests=$build/tests/gl/gl_tests
for exe in "$boxrecon" "$gl_tests"; do
  [[ -x $exe ]] || { echo "gpu_check: $exe is missing: build the release preset first" >&2; exit 1; }
  if ldd "$exe" | grep -q "not found"; then
    echo "gpu_check: $exe lacks shared libraries:" >&2
    ldd "$exe" | grep "not found" >&2
    exit 1
  fi
done
mkdir -p "$out"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
status=0

echo "== GL renderer (EGL device enumeration first, then Mesa surfaceless)"
"$boxrecon" sample --function ml --n 12 -o "$scratch/v.nrrd"
echo "0 0 0" | timeout 20 "$boxrecon" eval --filter m7 --volume "$scratch/v.nrrd" --points - \
  --device gl --verbose 2>&1 >/dev/null | tee "$out/renderer.txt"
grep -q "^GL device: " "$out/renderer.txt" || status=1
if grep -q "llvmpipe" "$out/renderer.txt"; then
  echo "gpu_check: warning: the renderer is llvmpipe, not the GPU (is the NVIDIA EGL vendor" \
       "file /usr/share/glvnd/egl_vendor.d/10_nvidia.json present?)" >&2
fi

echo "== gl-label tests (gl_tests but the Slow* SPEC compile; the CLI tests run this boxrecon)"
BOXRECON_UNDER_TEST=$boxrecon timeout 90 "$gl_tests" --gtest_brief=1 --gtest_filter="-*Slow*" 2>&1 | tee "$out/gl_tests.txt"
[[ ${PIPESTATUS[0]} -eq 0 ]] || status=1

echo "== boxrecon bench --device gl --json (GL beside the CPU, same run)"
timeout 120 "$boxrecon" bench --device gl --json | tee "$out/bench.json"
[[ ${PIPESTATUS[0]} -eq 0 ]] || status=1

echo "gpu_check: $([[ $status -eq 0 ]] && echo passed || echo FAILED); results in $out/"
exit $status
