// What a volume holds beyond its samples, for evaluation up to its faces (docs/runtime.md,
// "Boundaries"). The sampled box of a volume is, per axis a, the lattice coordinates
// lo_a = min_c off_c,a  <=  x_a  <=  hi_a = max_c off_c,a + d (N_a - 1): every lattice point in it
// is a sample. A boundary extends the samples to every lattice point:
//
//   strict   nothing: a point whose stencil leaves the samples is refused (std::out_of_range)
//   mirror   whole-sample mirror about the faces x_a = lo_a and x_a = hi_a (the face samples are
//            not repeated: ... c b | a b c ... y z | y x ...), repeated with period 2 (hi - lo):
//            scipy.ndimage's and ITK's 'mirror'. Only where these reflections map the lattice to
//            itself (BCC, FCC, Cartesian: always; a custom lattice: checked); elsewhere the clamp.
//   clamp    per coset, the nearest sample of the same coset along each axis (edge padding)
//
// mirror is the default of every command and of Python.
#pragma once
#include <array>
#include <cstddef>
#include <string_view>
#include <vector>

#include "runtime/lattice_volume.h"

namespace boxgen::runtime {

enum class Boundary { Strict, Mirror, Clamp };
inline constexpr Boundary kDefaultBoundary = Boundary::Mirror;
inline constexpr const char* kBoundaryChoices = "strict | mirror | clamp";

// "strict" | "mirror" | "clamp"; anything else: std::invalid_argument, one line.
Boundary parse_boundary(std::string_view text);
const char* boundary_name(Boundary b);

// Do the whole-sample reflections about the faces of a volume of these sizes keep the lattice?
bool mirror_keeps_lattice(const CosetLattice& lattice, const Sizes& sizes);

// Where each point of a volume grown by `cells` coset cells on every side reads its value: the
// storage index (in the volume's samples) of the sample the extension copies, for every point of
// the grown volume in its storage order. Mirror falls back to clamp where it does not keep the
// lattice; strict is std::invalid_argument (it extends nothing).
class Extension {
 public:
  Extension(const CosetLattice& lattice, const Sizes& sizes, int cells, Boundary b);
  // The grown volume's sizes per coset (N_a + 2 cells).
  const Sizes& sizes() const noexcept { return grown_; }
  // The boundary applied (clamp where mirror does not keep the lattice).
  Boundary applied() const noexcept { return applied_; }
  // Storage index of the sample under point (c, i, j, k) of the grown volume, i, j, k counted
  // from its first cell (index i of the grown volume is sample index i - cells).
  std::size_t source(int c, int i, int j, int k) const noexcept;

 private:
  // Per axis and coset, the lattice coordinate (mirror) or sample index (clamp) each grown index
  // reads.
  std::array<std::vector<int>, 3> fold_;  // [axis][c * grown + i]
  CosetLattice lattice_;
  Sizes sizes_, grown_;
  int cells_;
  Boundary applied_;
};

// The volume grown by `cells` coset cells on every side under boundary b (strict: the volume
// itself); the origin moves so that every sample keeps its world position.
template <class T>
LatticeVolume<T> extend(const LatticeVolume<T>& volume, int cells, Boundary b);

extern template LatticeVolume<float> extend<float>(const LatticeVolume<float>&, int, Boundary);
extern template LatticeVolume<double> extend<double>(const LatticeVolume<double>&, int, Boundary);

}  // namespace boxgen::runtime
