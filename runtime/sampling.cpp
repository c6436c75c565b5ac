#include "runtime/sampling.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace boxgen::runtime {

BccGrid cube_grid(int n, int margin) {
  if (n < 2)
    throw std::invalid_argument(
        fmt::format("density N = {} is too small: N^3 x 2 samples over [-1,1]^3 need N >= 2", n));
  if (margin < 0)
    throw std::invalid_argument(fmt::format("margin {} must not be negative", margin));
  const long long per_axis = static_cast<long long>(n) + 2 * static_cast<long long>(margin);
  if (per_axis > BccVolume<double>::kMaxSize)
    throw std::invalid_argument(fmt::format(
        "density N = {} with margin {} is too large ({} samples per coset and axis, at most {})", n,
        margin, per_axis, BccVolume<double>::kMaxSize));
  const double h = 1.0 / (n - 1);
  const double o = -1 - 2 * h * margin;
  const int size = static_cast<int>(per_axis);
  return {{size, size, size}, h, {o, o, o}};
}

template <class T>
BccVolume<T> sample_bcc(const ScalarFunction& f, const BccGrid& grid) {
  BccVolume<T> volume(grid.sizes, grid.h, grid.origin);
  const Sizes& n = grid.sizes;
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i)
        for (int c = 0; c < 2; ++c)
          volume(c, i, j, k) = to_sample<T>(f(volume.sample_position(c, i, j, k)));
  return volume;
}

LatticeGrid cube_lattice_grid(const CosetLattice& lattice, int n, int margin) {
  const BccGrid bcc = cube_grid(n, margin);  // the same checks of n and margin
  const double h = 2.0 / (lattice.period() * static_cast<double>(n - 1));
  const double o = -1 - lattice.period() * h * margin;
  return {lattice, bcc.sizes, h, {o, o, o}};
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
template BccVolume<float> sample_bcc<float>(const ScalarFunction&, const BccGrid&);
template BccVolume<double> sample_bcc<double>(const ScalarFunction&, const BccGrid&);

}  // namespace boxgen::runtime
