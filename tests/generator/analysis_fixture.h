// One analysis per preset, derived once per test binary (the exact checks run with it).
#pragma once
#include <map>
#include <memory>
#include <string>

#include "generator/analysis.h"
#include "generator/spec.h"

namespace boxgen::testing {

inline const Analysis& analysis_of(const std::string& preset) {
  static std::map<std::string, std::unique_ptr<Analysis>> cache;
  auto it = cache.find(preset);
  if (it == cache.end()) it = cache.emplace(preset, std::make_unique<Analysis>(analyze(parse_spec(preset)))).first;
  return *it->second;
}

inline const char* const kAllPresets[] = {"m7", "m8", "m12", "cart7", "fcc6", "tricubic", "hex3", "zp"};

}  // namespace boxgen::testing
