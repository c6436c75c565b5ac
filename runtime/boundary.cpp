#include "runtime/boundary.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <span>
#include <stdexcept>

#include "runtime/batch_threads.h"
#include "support/integer_math.h"

namespace boxgen::runtime {

using support::floor_div;

Boundary parse_boundary(std::string_view text) {
  if (text == "strict") return Boundary::Strict;
  if (text == "mirror") return Boundary::Mirror;
  if (text == "clamp") return Boundary::Clamp;
  throw std::invalid_argument(
      fmt::format("unknown boundary '{}': expected strict, mirror or clamp", text.substr(0, 40)));
}

const char* boundary_name(Boundary b) {
  switch (b) {
    case Boundary::Strict:
      return "strict";
    case Boundary::Mirror:
      return "mirror";
    case Boundary::Clamp:
      return "clamp";
  }
  return "?";
}

namespace {

// The faces of the sampled box along axis a (boundary.h): lo = 0 (coset 0's offset is the origin)
// and hi = max_c off_c,a + d (N_a - 1).
std::int64_t upper_face(const CosetLattice& lattice, const Sizes& sizes, int a) {
  int top = 0;
  for (const Offset& o : lattice.offsets()) top = std::max(top, o[static_cast<std::size_t>(a)]);
  return top +
         static_cast<std::int64_t>(lattice.period()) * (sizes[static_cast<std::size_t>(a)] - 1);
}

// x folded into [0, hi] by reflections about 0 and hi (period 2 hi).
std::int64_t fold(std::int64_t x, std::int64_t hi) {
  if (hi == 0) return 0;
  std::int64_t r = x - 2 * hi * floor_div(x, 2 * hi);  // in [0, 2 hi)
  return r <= hi ? r : 2 * hi - r;
}

}  // namespace

bool mirror_keeps_lattice(const CosetLattice& lattice, const Sizes& sizes) {
  // A reflection x_a -> 2 f - x_a keeps L when it maps one point of every coset of d Z^3 into L.
  for (int a = 0; a < 3; ++a)
    for (const std::int64_t face : {std::int64_t{0}, upper_face(lattice, sizes, a)})
      for (const Offset& o : lattice.offsets()) {
        std::array<std::int64_t, 3> p{o[0], o[1], o[2]};
        p[static_cast<std::size_t>(a)] = 2 * face - p[static_cast<std::size_t>(a)];
        if (!lattice.contains(p[0], p[1], p[2])) return false;
      }
  return true;
}

Extension::Extension(const CosetLattice& lattice, const Sizes& sizes, int cells, Boundary b)
    : lattice_(lattice), sizes_(sizes), cells_(cells), applied_(b) {
  if (b == Boundary::Strict) throw std::invalid_argument("the strict boundary extends no volume");
  if (cells < 0 || cells > LatticeVolume<double>::kMaxSize / 4)
    throw std::invalid_argument(fmt::format("cannot grow a volume by {} cells", cells));
  if (b == Boundary::Mirror && !mirror_keeps_lattice(lattice, sizes)) applied_ = Boundary::Clamp;
  const int k_count = lattice.coset_count();
  const int d = lattice.period();
  for (int a = 0; a < 3; ++a) {
    const auto sa = static_cast<std::size_t>(a);
    grown_[sa] = sizes[sa] + 2 * cells;
    const std::int64_t hi = upper_face(lattice, sizes, a);
    auto& table = fold_[sa];
    table.resize(static_cast<std::size_t>(k_count) * static_cast<std::size_t>(grown_[sa]));
    for (int c = 0; c < k_count; ++c)
      for (int i = 0; i < grown_[sa]; ++i) {
        const int sample = i - cells;
        const std::size_t at = static_cast<std::size_t>(c) * static_cast<std::size_t>(grown_[sa]) +
                               static_cast<std::size_t>(i);
        if (applied_ == Boundary::Clamp) {
          table[at] = std::clamp(sample, 0, sizes[sa] - 1);
        } else {
          const std::int64_t x =
              lattice.offsets()[static_cast<std::size_t>(c)][sa] + std::int64_t{d} * sample;
          table[at] = static_cast<int>(fold(x, hi));
        }
      }
  }
}

std::size_t Extension::source(int c, int i, int j, int k) const noexcept {
  const auto k_count = static_cast<std::size_t>(lattice_.coset_count());
  const auto at = [&](int a, int index) {
    return fold_[static_cast<std::size_t>(a)]
                [static_cast<std::size_t>(c) *
                     static_cast<std::size_t>(grown_[static_cast<std::size_t>(a)]) +
                 static_cast<std::size_t>(index)];
  };
  const int x = at(0, i), y = at(1, j), z = at(2, k);
  const auto n0 = static_cast<std::size_t>(sizes_[0]), n1 = static_cast<std::size_t>(sizes_[1]);
  if (applied_ == Boundary::Clamp)
    return static_cast<std::size_t>(c) +
           k_count * (static_cast<std::size_t>(x) +
                      n0 * (static_cast<std::size_t>(y) + n1 * static_cast<std::size_t>(z)));
  // Mirror: the folded lattice point is a sample (every lattice point of the sampled box is).
  const int to = lattice_.coset_of(x, y, z);
  const Offset& o = lattice_.offsets()[static_cast<std::size_t>(to)];
  const int d = lattice_.period();
  return static_cast<std::size_t>(to) +
         k_count * (static_cast<std::size_t>((x - o[0]) / d) +
                    n0 * (static_cast<std::size_t>((y - o[1]) / d) +
                          n1 * static_cast<std::size_t>((z - o[2]) / d)));
}

template <class T>
LatticeVolume<T> extend(const LatticeVolume<T>& volume, int cells, Boundary b) {
  if (b == Boundary::Strict || cells == 0) return volume;
  const Extension e(volume.lattice(), volume.sizes(), cells, b);
  Vec3 origin = volume.origin();
  for (int a = 0; a < 3; ++a)
    origin[static_cast<std::size_t>(a)] -=
        volume.period() * volume.axis_spacing()[static_cast<std::size_t>(a)] * cells;
  LatticeVolume<T> out(volume.lattice(), e.sizes(), volume.axis_spacing(), origin,
                       std::vector<T>(static_cast<std::size_t>(volume.coset_count()) *
                                      static_cast<std::size_t>(e.sizes()[0]) *
                                      static_cast<std::size_t>(e.sizes()[1]) *
                                      static_cast<std::size_t>(e.sizes()[2])));
  const std::span<const T> in = volume.samples();
  const Sizes& n = e.sizes();
#pragma omp parallel for schedule(dynamic, 1) num_threads(batch_threads())
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i)
        for (int c = 0; c < volume.coset_count(); ++c) out(c, i, j, k) = in[e.source(c, i, j, k)];
  return out;
}

template LatticeVolume<float> extend<float>(const LatticeVolume<float>&, int, Boundary);
template LatticeVolume<double> extend<double>(const LatticeVolume<double>&, int, Boundary);

}  // namespace boxgen::runtime
