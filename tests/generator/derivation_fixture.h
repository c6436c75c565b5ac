// One derivation per preset, derived once per test binary process. derivation_of() skips the
// default exact checks (they dominate the time and every test process would repeat them); the
// checks run in verified_derivation_of(), which AnalyzePreset.MatchesTheLiterature uses for every
// preset, and are themselves tested on broken forms in piece_checks_test.cpp.
#pragma once
#include <map>
#include <memory>
#include <string>

#include "generator/derivation.h"
#include "generator/spec.h"

namespace boxgen::generator::fixture {

namespace detail {
inline const Derivation& cached_derivation(const std::string& preset, bool verify) {
  static std::map<std::pair<std::string, bool>, std::unique_ptr<Derivation>> cache;
  const auto key = std::make_pair(preset, verify);
  auto it = cache.find(key);
  if (it == cache.end()) {
    DerivationOptions options;
    options.verify = verify;
    it =
        cache.emplace(key, std::make_unique<Derivation>(derive(parse_spec(preset), options))).first;
  }
  return *it->second;
}
}  // namespace detail

// Properties, piecewise form and structure (no exact checks).
inline const Derivation& derivation_of(const std::string& preset) {
  return detail::cached_derivation(preset, false);
}
// The same with the default exact checks run (a failing check throws InternalError).
inline const Derivation& verified_derivation_of(const std::string& preset) {
  return detail::cached_derivation(preset, true);
}

inline const char* const kAllPresets[] = {"m7",   "m8",       "m12",  "cart7",
                                          "fcc6", "tricubic", "hex3", "zp"};

}  // namespace boxgen::generator::fixture
