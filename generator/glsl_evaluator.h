// The GLSL printer of an evaluator (docs/gpu.md): the tables of generator/evaluator_tables.h as
// flat const arrays, every orbit's scheduled code as one function per path (GLSL has no
// templates), and the glue of templates/evaluator.glsl.fmt (locate, fetch, back to the lattice
// frame; its loops unrolled here, docs/design.md §16) behind NAME_value, NAME_value_gradient and
// NAME_value_gradient_hessian.
#pragma once
#include <string>
#include <vector>

#include "generator/derivation.h"
#include "generator/polynomial_code.h"

namespace boxgen::generator {

// The text of NAME.glsl; `banner` opens it, `cost_lines` are the "//" lines of the C++ header's
// counts. float, vecN, matN, or with `double_precision` double, dvecN, dmatN.
std::string glsl_evaluator(const Derivation& a, const std::string& banner, const std::string& name,
                           const std::vector<OrbitCode>& orbits,
                           const std::vector<std::string>& cost_lines, bool double_precision);

}  // namespace boxgen::generator
