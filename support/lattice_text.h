// Integer rows and lattices as users write them: a SPEC's directions, --lattice, Python's
// lattice=, a volume file's lattice key. One parser for the generator (generator/spec.cpp) and
// the runtime (runtime/coset_lattice.cpp), so both accept the same spellings and word their
// errors alike: rows separated by ';' (a trailing ';' allowed), a row's entries by ',' and/or
// blanks; a lattice is a name (bcc, fcc or cartesian, in any case) or the rows of G.
// Every error is a TextError: one line, repeating the user's text printable and bounded.
#pragma once
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace boxgen::support {

struct TextError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

using IntegerRows = std::vector<std::vector<std::int64_t>>;

// What one kind of row list is called in messages and how large its entries may be.
struct RowSyntax {
  std::string_view list;       // "SPEC" or "lattice"
  std::string_view row;        // "direction" or "lattice row"
  std::int64_t max_abs;        // the largest magnitude of an entry
  std::string_view too_large;  // why larger entries are refused ("to derive")
};

// At most `max_rows` rows of integers ([+-]digits), all of one length, 2 or 3 (2-D or 3-D).
IntegerRows parse_rows(std::string_view text, const RowSyntax& syntax, std::size_t max_rows);

// A lattice as written: its name, or the rows of G (n rows of n entries, n = 2 or 3, entries at
// most `max_entry` in magnitude). `dimension` (2 or 3) is the one the caller needs and
// `because` says why, completing "the lattice is 2-dimensional but ...": "the directions are
// 3-dimensional", "volumes are 3-D".
struct LatticeText {
  std::string name;  // "bcc", "fcc" or "cartesian"; empty when G's rows are given
  IntegerRows rows;  // the rows of G
};
LatticeText parse_lattice_text(std::string_view text, int dimension, std::string_view because,
                               std::int64_t max_entry);

// A blank: a space, tab or line break.
bool is_blank(char c);
// `text` in lower case (ASCII).
std::string lower(std::string_view text);
// Blanks (spaces, tabs, line breaks) removed at both ends.
std::string_view trim(std::string_view text);
// User text inside a one-line message: printable ASCII only ('?' for anything else), at most 40
// characters (then "...").
std::string echo(std::string_view text);

}  // namespace boxgen::support
