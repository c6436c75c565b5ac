// CosetLattice::parse, apart from coset_lattice.cpp: a filter compiled at run time (loader/) links
// the runtime's archive alone, and the objects it pulls in must not need support/'s text parser.
#include "runtime/coset_lattice.h"
#include "runtime/lattice_limits.h"
#include "support/lattice_text.h"

namespace boxgen::runtime {

CosetLattice CosetLattice::parse(std::string_view text) {
  // from_rows refuses larger entries with the same bound.
  const support::LatticeText lattice =
      support::parse_lattice_text(text, 3, "volumes are 3-D", kMaxLatticeEntry);
  if (lattice.name == "bcc") return bcc();
  if (lattice.name == "fcc") return fcc();
  if (lattice.name == "cartesian") return cartesian();
  IntRows rows{};
  for (std::size_t r = 0; r < 3; ++r)
    for (std::size_t c = 0; c < 3; ++c) rows.at(r).at(c) = lattice.rows.at(r).at(c);
  return from_rows(rows);
}

}  // namespace boxgen::runtime
