#include "runtime/sampling.h"

#include <fmt/format.h>

#include <stdexcept>

namespace boxgen::runtime {

LatticeGrid cube_lattice_grid(const CosetLattice& lattice, int n, int margin) {
  if (n < 2)
    throw std::invalid_argument(fmt::format(
        "density N = {} is too small: N^3 samples per coset over [-1,1]^3 need N >= 2", n));
  if (margin < 0)
    throw std::invalid_argument(fmt::format("margin {} must not be negative", margin));
  const long long per_axis = static_cast<long long>(n) + 2 * static_cast<long long>(margin);
  if (per_axis > LatticeVolume<double>::kMaxSize)
    throw std::invalid_argument(fmt::format(
        "density N = {} with margin {} is too large ({} samples per coset and axis, at most {})", n,
        margin, per_axis, LatticeVolume<double>::kMaxSize));
  const double h = 2.0 / (lattice.period() * static_cast<double>(n - 1));
  const double o = -1 - lattice.period() * h * margin;
  const int size = static_cast<int>(per_axis);
  return {lattice, {size, size, size}, h, {o, o, o}};
}

template <class T>
LatticeVolume<T> sample_lattice(const ScalarFunction& f, const LatticeGrid& grid) {
  LatticeVolume<T> volume(grid.lattice, grid.sizes, grid.h, grid.origin);
  const Sizes& n = grid.sizes;
  const int cosets = volume.coset_count();
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i)
        for (int c = 0; c < cosets; ++c)
          volume(c, i, j, k) = to_sample<T>(f(volume.sample_position(c, i, j, k)));
  return volume;
}

template LatticeVolume<float> sample_lattice<float>(const ScalarFunction&, const LatticeGrid&);
template LatticeVolume<double> sample_lattice<double>(const ScalarFunction&, const LatticeGrid&);

}  // namespace boxgen::runtime
