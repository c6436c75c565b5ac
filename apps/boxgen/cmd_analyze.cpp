#include <iostream>

#include "apps/boxgen/commands.h"
#include "generator/analysis.h"

namespace boxgen::cli {

int run_analyze(const Common& c, bool verify) {
  const BoxSplineSpec spec = parse_spec(c.spec, c.lattice);
  const Analysis a = analyze(spec, {verify});
  if (c.json)
    print_json(to_json(a));
  else
    std::cout << to_table(a);
  return 0;
}

}  // namespace boxgen::cli
