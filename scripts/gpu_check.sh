#!/usr/bin/env bash
# The checks that need a GPU (docs/gpu.md): the renderer EGL gives, the gl-label tests and the
# GLSL exactness tests (gpu_tests) on it, `boxrecon bench --device gl --json` (M7 float
# evaluations per second and over the fetch floor, ms per 1024 x 1024 render) and, where nvcc
# exists, the emitted CUDA headers built by nvcc and run on the device against their host build
# (tests/gpu/cuda_device_check.cu). Builds nothing else: BUILD_DIR is a release build made
# elsewhere (its binaries and their shared libraries carried over; the machine brings its own GL
# driver and EGL vendor files). Under 8 minutes.
#
#   scripts/gpu_check.sh BUILD_DIR [OUT_DIR]
#
# OUT_DIR (default ./gpu_check) receives renderer.txt, gl_tests.txt, gpu_tests.txt, bench.json,
# programs/ (bench's kernels as compiled: source, link log and binary; BOXGEN_GL_DUMP),
# programs.txt (what each binary shows of its assembly) and cuda.txt.
set -uo pipefail

build=${1:?usage: scripts/gpu_check.sh BUILD_DIR [OUT_DIR]}
out=${2:-gpu_check}
boxrecon=$build/apps/boxrecon
gl_tests=$build/tests/gl/gl_tests
gpu_tests=$build/tests/gpu/gpu_tests
source_dir=$(cd "$(dirname "$0")/.." && pwd)
for exe in "$boxrecon" "$gl_tests" "$gpu_tests"; do
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

# Not the Slow* SPEC compile, nor the kernels' syntax trees (KernelIndexing*: glslang reads the
# text, the same on any machine, and CI runs them).
echo "== gl-label tests (gl_tests but Slow* and KernelIndexing*; the CLI tests run this boxrecon)"
BOXRECON_UNDER_TEST=$boxrecon timeout 90 "$gl_tests" --gtest_brief=1 \
  --gtest_filter="-*Slow*:*KernelIndexing*" 2>&1 | tee "$out/gl_tests.txt"
[[ ${PIPESTATUS[0]} -eq 0 ]] || status=1

echo "== boxrecon bench --device gl --json (GL beside the CPU, same run; its kernels to programs/)"
BOXGEN_GL_DUMP=$out/programs timeout 200 "$boxrecon" bench --device gl --json | tee "$out/bench.json"
[[ ${PIPESTATUS[0]} -eq 0 ]] || status=1
# What the driver's compiler made of each kernel: its binary's printable lines that look like
# assembly (NV_gpu_program5's "!!NV" header, local arrays "lmem"), if the binary holds any text.
for bin in "$out"/programs/*.bin; do
  [[ -e $bin ]] || continue
  printf '%s: %s bytes, "!!NV" lines %s, "lmem" mentions %s\n' "$(basename "$bin")" \
    "$(stat -c %s "$bin")" "$(grep -a -c '!!NV' "$bin")" "$(grep -a -o 'lmem' "$bin" | wc -l)"
done | tee "$out/programs.txt"

echo "== gpu-label exactness (gpu_tests: GLSL float and double on this renderer, CUDA host build)"
timeout 180 "$gpu_tests" --gtest_brief=1 2>&1 | tee "$out/gpu_tests.txt"
[[ ${PIPESTATUS[0]} -eq 0 ]] || status=1

if command -v nvcc > /dev/null; then
  echo "== CUDA: the emitted headers built by nvcc, run on the device against their host build"
  emitted=$build/tests/gpu/emitted
  { nvcc --version | tail -1 &&
    timeout 240 nvcc -std=c++17 -O3 -arch=native -I "$emitted" -I "$source_dir" \
      "$source_dir/tests/gpu/cuda_device_check.cu" -o "$scratch/cuda_device_check" &&
    timeout 60 "$scratch/cuda_device_check" &&
    timeout 60 nvcc -std=c++17 -O3 -arch=native -I "$emitted" -I "$source_dir" -c \
      "$source_dir/examples/gpu/m7_kernel.cu" -o "$scratch/m7_kernel.o" &&
    echo "examples/gpu/m7_kernel.cu: built by nvcc"; } 2>&1 | tee "$out/cuda.txt"
  [[ ${PIPESTATUS[0]} -eq 0 ]] || status=1
else
  echo "== CUDA: no nvcc here; the CUDA device check is not run" | tee "$out/cuda.txt"
fi

echo "gpu_check: $([[ $status -eq 0 ]] && echo passed || echo FAILED); results in $out/"
exit $status
