// SPEC: what the user asks the generator about: a direction matrix Xi (columns) on a lattice.
// A SPEC is a preset name (`boxgen presets`) or a direction list "1,1,1; 1,-1,-1; ..." with one
// direction per ';'. The lattice is bcc | fcc | cartesian | "<rows of G>" (rows separated by ';');
// by default the preset's lattice, else cartesian.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "generator/lattice.h"

namespace boxgen::generator {

inline constexpr int kMaxDirections = 32;

struct BoxSplineSpec {
  std::string name;       // preset name, or "custom"
  std::string text;       // the SPEC as the user gave it
  IntColumns directions;  // the columns xi of Xi, in the given order
  Lattice lattice;

  int dimension() const { return lattice.dimension(); }
  int count() const { return static_cast<int>(directions.size()); }
  std::string directions_text() const;  // "1,1,1; 1,-1,-1; ..."
};

struct PresetInfo {
  std::string name;
  std::string directions;  // direction list in SPEC syntax
  std::string lattice;     // lattice name
  std::string description;
};

const std::vector<PresetInfo>& presets();

// Parses and validates a SPEC. Throws InputError with a one-line message on any problem:
// malformed text, unknown preset, wrong dimension, zero or rank-deficient matrix, a direction
// not in the lattice, more than kMaxDirections directions, entries too large to derive.
BoxSplineSpec parse_spec(std::string_view spec, std::string_view lattice_text = "");

// The largest k dividing every entry of Xi and of G: (Xi, G) is k times the reduced pair
// (Xi / k, G / k), whose spline it is, stretched by k (generator/common_scale.h).
std::int64_t common_scale(const BoxSplineSpec& spec);

// `text` on one line: each run of blanks (spaces, tabs, line breaks) one space, none at the ends.
// A SPEC, lattice or shell list may be given over several lines; emitted files quote it so, as
// the text of a comment line and of the command that reproduces them.
std::string one_line(std::string_view text);

// Parses bcc | fcc | cartesian | "<rows of G>" for the given dimension.
Lattice parse_lattice(std::string_view text, int dimension);

}  // namespace boxgen::generator
