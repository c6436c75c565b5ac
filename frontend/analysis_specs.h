// The SPECs of the analysis commands (metrics, kernel, spectrum): each "SPEC" or "SPEC@LATTICE"
// (LATTICE spelt as --lattice takes it, which is the default for a SPEC without '@'), named in
// tables, JSON keys and legends by its --label or else by the text as given. Errors about one SPEC
// name it.
#pragma once
#include <string>
#include <vector>

#include "generator/error.h"
#include "generator/spec.h"

namespace boxgen::frontend {

struct NamedSpec {
  std::string text;  // as given, "SPEC@LATTICE" included
  std::string key;   // its --label, else `text`
  generator::BoxSplineSpec spec;
};

// Parses every SPEC before any work, so a bad one fails first. Throws InputError with one line:
// a SPEC's own error prefixed by 'SPEC', a --label count other than the SPEC count, an empty
// label, or two SPECs with one key.
std::vector<NamedSpec> parse_named_specs(const std::vector<std::string>& texts,
                                         const std::string& lattice,
                                         const std::vector<std::string>& labels);

// Runs `work` (a derivation about the SPEC given as `text`); an InputError it throws comes back
// prefixed with the SPEC.
template <class Work>
auto about_spec(const std::string& text, Work&& work) -> decltype(work()) {
  try {
    return work();
  } catch (const generator::InputError& e) {
    throw generator::InputError("'" + text.substr(0, 60) + "': " + e.what());
  }
}

}  // namespace boxgen::frontend
