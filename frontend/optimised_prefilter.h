// q1opt and q2opt (docs/design.md §19): the prefilters on the shells of q1 and q2 (one weight per
// symmetry orbit) whose free parameters minimise the integrated error kernel over the Nyquist
// region, joining the exact family of the generator (generator/prefilter.h) and the numerical
// optimisation of the analysis (analysis/optimal_prefilter.h).
#pragma once
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "analysis/optimal_prefilter.h"
#include "generator/codegen/emitter.h"
#include "generator/prefilter.h"

namespace boxgen::frontend {

struct OptimisedPrefilter {
  // The weights particular + sum_i t_i basis_i with t the optimised doubles taken exactly: exact
  // rationals that satisfy the moment conditions exactly. The programs print and use their
  // nearest doubles.
  generator::Prefilter prefilter;
  generator::PrefilterFamily family;
  analysis::OptimisedParameters optimisation;
};

// Is `name` q1opt or q2opt?
bool is_optimised_prefilter(std::string_view name);
// q1opt or q2opt of the SPEC; InputError (one line) like named_prefilter. q1_shells: the shells
// of q1 (q2: these and the next), as `boxgen emit --shells` takes them; empty: the smallest with
// a prefilter of full order (quasi_interpolation_shells).
OptimisedPrefilter optimised_prefilter(const generator::BoxSplineSpec& spec, std::string_view name,
                                       const std::vector<int>& q1_shells = {});

// The same as a table for NAME_prefilters.hpp (`boxgen emit`, the run-time filters of loader/);
// none where the shells hold no prefilter of full order (the header then says why there is no q1
// or q2 either).
std::optional<generator::OptimisedPrefilterTable> optimised_table(
    const generator::BoxSplineSpec& spec, std::string_view name,
    const std::vector<int>& q1_shells = {});

}  // namespace boxgen::frontend
