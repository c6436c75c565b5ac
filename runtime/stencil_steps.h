// The stencil of an orbit as steps from its first sample, in the orbit's reference frame: what
// lets the SIMD path compute where every sample of a lane's stencil lies from that lane's first
// sample and its cell's signed permutation, instead of reading a table per lane and sample
// (runtime/simd_kernels-inl.h, docs/design.md §13).
//
// Cell c maps x to x_ref = g_c (x - t_c) + a_c, (g x)_i = sign_i x_perm_i, and its stencil values
// are in the order of its orbit's (kOffsets[c][k]), so the step of sample k from sample 0,
// g_c (kOffsets[c][k] - kOffsets[c][0]), is the same for every cell of the orbit. The emitted
// tables have that structure by construction; it is computed and checked here from them (a
// header that lacked it takes the table path), not assumed.
#pragma once
#include <cstddef>
#include <iterator>

namespace boxgen::runtime {

template <class Tr>
struct StencilSteps {
  static constexpr int kOrbits = static_cast<int>(std::size(Tr::kOrbitStencilSize));
  // step[o][k][i]: sample k of orbit o minus sample 0, in the reference frame.
  int step[kOrbits][Tr::kStencilSize][Tr::kDimension] = {};
  // Every cell of each orbit has the same steps.
  bool consistent = true;
  // Every step's coordinates share one parity (on BCC, a step flips the coset when it is odd).
  bool same_parity = true;
  // Runs: where an orbit's samples come in groups k = kRun g + j (j < kRun) that differ by
  // j run_step[o] along reference axis run_axis[o], and every cell of the orbit maps that axis to
  // storage axis 0, a group lies in storage within kRun run_step[o] consecutive samples, so a lane
  // loads it with vector loads instead of kRun gathers (simd_kernels-inl.h). run_axis[o] is -1
  // where the orbit has no runs.
  static constexpr int kRun = 4;
  int run_axis[kOrbits] = {};
  int run_step[kOrbits] = {};
};

// The runs of orbit o along reference axis r (StencilSteps::run_axis), their step, or 0.
template <class Tr>
constexpr int run_step_along(const StencilSteps<Tr>& s, int o, int r) {
  constexpr int kRun = StencilSteps<Tr>::kRun;
  for (int c = 0; c < Tr::kCellCount; ++c)
    if (Tr::kCells[c].orbit == o && Tr::kCells[c].perm[r] != 0) return 0;
  const int size = Tr::kOrbitStencilSize[o];
  if (size % kRun != 0) return 0;
  const int u = s.step[o][1][r] - s.step[o][0][r];
  if (u != 1 && u != 2) return 0;  // a run's load covers kRun u samples (at most 8)
  for (int k = 0; k < size; ++k)
    for (int i = 0; i < Tr::kDimension; ++i) {
      const int j = k % kRun, first = k - j;
      if (s.step[o][k][i] != s.step[o][first][i] + (i == r ? j * u : 0)) return 0;
    }
  return u;
}

template <class Tr>
constexpr StencilSteps<Tr> stencil_steps() {
  constexpr int n = Tr::kDimension;
  StencilSteps<Tr> s{};
  bool seen[StencilSteps<Tr>::kOrbits] = {};
  for (int c = 0; c < Tr::kCellCount; ++c) {
    const auto& cell = Tr::kCells[c];
    const int o = cell.orbit;
    for (int k = 0; k < Tr::kOrbitStencilSize[o]; ++k) {
      int parity = -1;
      for (int i = 0; i < n; ++i) {
        const int p = cell.perm[i];
        const int step = cell.sign[i] * (Tr::kOffsets[c][k][p] - Tr::kOffsets[c][0][p]);
        if (!seen[o])
          s.step[o][k][i] = step;
        else if (s.step[o][k][i] != step)
          s.consistent = false;
        const int bit = step & 1;
        if (parity >= 0 && bit != parity) s.same_parity = false;
        parity = bit;
      }
    }
    seen[o] = true;
  }
  for (int o = 0; o < StencilSteps<Tr>::kOrbits; ++o) {
    s.run_axis[o] = -1;
    for (int r = 0; r < n && s.run_axis[o] < 0; ++r) {
      s.run_step[o] = run_step_along(s, o, r);
      if (s.run_step[o] != 0) s.run_axis[o] = r;
    }
  }
  return s;
}

template <class Tr>
inline constexpr StencilSteps<Tr> kStencilSteps = stencil_steps<Tr>();

}  // namespace boxgen::runtime
