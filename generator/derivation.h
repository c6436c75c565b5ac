// `boxgen analyze`: everything the generator derives about a box spline on its lattice, with the
// exact checks that run by default (docs/design.md §3-§5, §7). Every number here is derived, not
// looked up.
#pragma once
#include <nlohmann/json.hpp>

#include "generator/box_spline_properties.h"
#include "generator/piece_checks.h"
#include "generator/piecewise_form.h"
#include "generator/spline_regions.h"

namespace boxgen::generator {

struct DerivationChecks {
  bool full = false;           // every check on every cell (else reduced by symmetry)
  bool methods_agree = false;  // truncated power == directional integration, cell by cell
  bool integral_is_one = false;
  bool symmetric = false;
  bool partition_of_unity = false;
  ContinuityReport continuity;
  double seconds = 0;
};

struct Derivation {
  BoxSplineSpec spec;
  BoxSplineProperties properties;
  PiecewiseForm form;  // by the truncated power
  SplineStructure structure;
  int pieces = 0;
  DerivationChecks checks;
  double derivation_seconds = 0;  // derivation and default checks, wall clock
};

struct DerivationOptions {
  bool verify = true;  // run the exact checks (a failure throws InternalError)
  // By default the integral and continuity checks visit one cell per symmetry orbit (exact,
  // since symmetry itself is checked on every cell); full visits every cell.
  bool full_checks = false;
  ProgressFn progress;     // stage, done, total; empty for none
  double max_seconds = 0;  // refuse what the cost estimate puts beyond this (0: the default limit)
  double max_bytes = 0;    // the same for memory (0: the machine's available memory)
};

Derivation derive(const BoxSplineSpec& spec, const DerivationOptions& options = {});
nlohmann::json to_json(const Derivation& a);
std::string to_table(const Derivation& a);

}  // namespace boxgen::generator
