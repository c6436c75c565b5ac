// A 3-D sampling lattice L = G Z^3 (G integer, non-singular) as the runtime stores it: K cosets of
// the Cartesian lattice d Z^3, where d is the smallest integer with d Z^3 inside L and
// K = d^3 / |det G|. Coset c is the set off_c + d Z^3 (offsets in lattice units).
//
//   bcc        G rows (-1,1,1; 1,-1,1; 1,1,-1)  d = 2, K = 2, offsets (0,0,0) (1,1,1)
//   fcc        G rows (1,1,0; 1,0,1; 0,1,1)     d = 2, K = 4, offsets (0,0,0) (1,1,0) (1,0,1)
//   (0,1,1) cartesian  G = I                            d = 1, K = 1, offset (0,0,0) custom     any
//   G: d, K and the offsets (every point of L in [0, d)^3, in lexicographic order
//              by z, then y, then x) are derived here.
//
// The same lattices as the generator's (generator/lattice.h; G's rows are written the same way,
// "a,b,c; d,e,f; g,h,i"), derived again with plain integers: the runtime includes no generator
// code.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace boxgen::runtime {

using IntRows = std::array<std::array<std::int64_t, 3>, 3>;
using Offset = std::array<int, 3>;

class CosetLattice {
 public:
  // Largest coset period d accepted for a custom lattice (d^3 residues are tabulated).
  static constexpr int kMaxPeriod = 64;

  static CosetLattice bcc();
  static CosetLattice fcc();
  static CosetLattice cartesian();
  // The lattice of the rows of G. Throws std::invalid_argument (one line) if G is singular, an
  // entry exceeds kMaxLatticeEntry (runtime/lattice_limits.h) in magnitude, or d exceeds
  // kMaxPeriod. Named "bcc", "fcc" or "cartesian"
  // (with those lattices' offsets) when G generates one of them, "custom" otherwise.
  static CosetLattice from_rows(const IntRows& rows);
  // Its name (any case) or G's rows, as support/lattice_text.h reads them; std::invalid_argument.
  static CosetLattice parse(std::string_view text);

  // The lattice with the same points but these coset offsets, in this order (a file's
  // coset_offsets). Throws std::invalid_argument (one line) unless they are K lattice points, one
  // in each coset of d Z^3.
  CosetLattice with_offsets(const std::vector<Offset>& offsets) const;

  const std::string& name() const noexcept { return name_; }
  // The name as messages write it: "BCC", "FCC", "Cartesian" or "custom".
  std::string label() const;
  const IntRows& rows() const noexcept { return rows_; }
  int period() const noexcept { return d_; }                                      // d
  int coset_count() const noexcept { return static_cast<int>(offsets_.size()); }  // K
  const std::vector<Offset>& offsets() const noexcept { return offsets_; }
  std::int64_t determinant() const noexcept { return det_; }  // |det G|

  // The coset holding integer point p, or -1 when p is not a lattice point.
  int coset_of(std::int64_t x, std::int64_t y, std::int64_t z) const noexcept {
    return table_[index_of(residue(x), residue(y), residue(z))];
  }
  bool contains(std::int64_t x, std::int64_t y, std::int64_t z) const noexcept {
    return coset_of(x, y, z) >= 0;
  }

  // "a,b,c; d,e,f; g,h,i" and "(x,y,z) (x,y,z) ...": the NRRD key/values lattice_rows and
  // coset_offsets.
  std::string rows_text() const;
  std::string offsets_text() const;

  // Same points and the same offsets in the same order.
  bool operator==(const CosetLattice& other) const noexcept {
    return offsets_ == other.offsets_ && d_ == other.d_ && det_ == other.det_;
  }

 private:
  CosetLattice() = default;
  // Position of the residues (rx, ry, rz) in table_ (x fastest).
  std::size_t index_of(int rx, int ry, int rz) const noexcept {
    const auto d = static_cast<std::size_t>(d_);
    return static_cast<std::size_t>(rx) +
           d * (static_cast<std::size_t>(ry) + d * static_cast<std::size_t>(rz));
  }
  int residue(std::int64_t x) const noexcept {
    const std::int64_t r = x % d_;
    return static_cast<int>(r < 0 ? r + d_ : r);
  }
  void tabulate();

  std::string name_;
  IntRows rows_{};
  int d_ = 1;
  std::int64_t det_ = 1;
  std::vector<Offset> offsets_;
  std::vector<int> table_;  // coset of each residue class (x mod d) + d (y mod d) + d^2 (z mod d)
};

// Do two lattices hold the same points (whatever the order of their cosets)?
bool same_points(const CosetLattice& a, const CosetLattice& b);

}  // namespace boxgen::runtime
