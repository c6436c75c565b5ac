#!/usr/bin/env bash
# Installs every Debian package boxgen needs to build, test and benchmark.
# Idempotent: apt-get skips what is already present. Run as root on Debian 12.
set -euo pipefail
PACKAGES=(
  build-essential cmake pkg-config git
  ninja-build                           # the presets' build tool: it starts a target's compiles before its libraries link
  libginac-dev libcln-dev               # exact rationals (CLN) in the generator; GiNaC prints `boxgen pieces`
  libfmt-dev                            # code templates and formatting
  nlohmann-json3-dev                    # --json output
  libcli11-dev                          # command-line parsing
  libgtest-dev googletest               # unit tests
  libbenchmark-dev                      # benchmarks
  libteem-dev                           # NRRD volume files (runtime)
  zlib1g-dev libbz2-dev                 # length check of gzip/bzip2 NRRD data (runtime/nrrd_io.cpp)
  gnuplot-nox                           # figures of kernels and spectra (boxgen kernel/spectrum)
  libpng-dev                            # PNG images of renders and slices
  libnifti2-dev                         # NIfTI-1/2 volumes (.nii, .nii.gz) read by the runtime (runtime/nifti_io.cpp)
  mricron-data                          # MRI templates (ch2better.nii.gz): the Fig. 10 replica and the NIfTI test on a shipped file
  libhwy-dev                            # SIMD batch path of the runtime (runtime/simd_batch.cpp)
  libfftw3-dev                          # FFTW3: --prefilter interp's transforms (runtime/interpolation.cpp)
  clang libclang-rt-14-dev libomp-dev   # libFuzzer targets (label: fuzz); libomp: OpenMP under clang
  clang-format-14 clang-tidy-14         # formatting and static analysis (scripts/lint.sh, in CI)
  libegl-dev libopengl-dev libgl-dev    # EGL and OpenGL 4.5 headers and loaders: boxrecon --device gl (runtime/gl)
  libgl1-mesa-dri                       #   and the GLSL tests (labels gl, gpu), on Mesa's llvmpipe without a GPU
  glslang-tools                         # glslangValidator: the syntax tree of the GL kernels, checked for arrays indexed at run time (tests/gl)
  python3 python3-numpy                 # the Python module boxgen (python/), for Debian's /usr/bin/python3,
  pybind11-dev python3-pybind11         #   NumPy arrays in and out, bound with pybind11
  python3-dask python3-distributed      # boxgen.dask: chunked resampling on dask (local or a cluster)
  python3-pytest                        # the Python tests (label python)
  python3-scipy                         # scripts/compare_scipy.py and scripts/scipy_tricubic_values.py: boxgen beside scipy
  python3-nibabel                       # scripts/fig10_scipy.py reads the MRI template; the tests read boxrecon's NIfTI output
)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  export DEBIAN_FRONTEND=noninteractive
  sudo=""
  if [ "$(id -u)" != 0 ]; then sudo="sudo"; fi
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
