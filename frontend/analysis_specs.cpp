#include "frontend/analysis_specs.h"

#include <fmt/core.h>

#include <set>

namespace boxgen::frontend {

std::vector<NamedSpec> parse_named_specs(const std::vector<std::string>& texts,
                                         const std::string& lattice,
                                         const std::vector<std::string>& labels) {
  if (!labels.empty() && labels.size() != texts.size())
    generator::fail_input(fmt::format("got {} --label for {} SPECs: give one per SPEC, in order",
                                      labels.size(), texts.size()));
  std::vector<NamedSpec> out;
  std::set<std::string> keys;
  for (std::size_t i = 0; i < texts.size(); ++i) {
    const std::string& text = texts[i];
    const std::string key = labels.empty() ? text : labels[i];
    if (key.empty()) generator::fail_input(fmt::format("--label {} is empty", i + 1));
    if (!keys.insert(key).second)
      generator::fail_input(fmt::format("two SPECs are both named '{}': give each its own --label",
                                        key.substr(0, 60)));
    // The lattice after the first '@' (no SPEC or lattice text contains one), else --lattice.
    const std::size_t at = text.find('@');
    generator::BoxSplineSpec spec = about_spec(text, [&] {
      if (at != std::string::npos && text.find_first_not_of(" \t", at + 1) == std::string::npos)
        generator::fail_input(
            "no lattice after '@': expected bcc, fcc, cartesian or the rows of G");
      return at == std::string::npos
                 ? generator::parse_spec(text, lattice)
                 : generator::parse_spec(text.substr(0, at), text.substr(at + 1));
    });
    out.push_back({text, key, std::move(spec)});
  }
  return out;
}

}  // namespace boxgen::frontend
