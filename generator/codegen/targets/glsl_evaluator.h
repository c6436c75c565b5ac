// The GLSL printer of an evaluator (docs/gpu.md): the tables of
// generator/codegen/targets/evaluator_tables.h as flat const arrays, every orbit's scheduled code
// as one function per path (GLSL has no templates), and the glue of templates/evaluator.glsl.fmt
// (locate, fetch, back to the lattice frame; its loops unrolled here, docs/design.md §16) behind
// NAME_value, NAME_value_gradient and NAME_value_gradient_hessian.
#pragma once
#include <string>
#include <vector>

#include "generator/codegen/strategies/polynomial_code.h"
#include "generator/derivation.h"

namespace boxgen::generator {

// NAME.glsl, whose tables are `const` arrays so that it stands alone; and the same evaluator with
// the tables indexed at run time (by the point's cell, and with several orbits by its orbit) in
// one read-only storage block NAME_Tables at binding BOXGEN_TABLES_BINDING (a macro the shader
// defines before the text), for a device that uploads `block` once (docs/gpu.md, "Tables on the
// device"). The block's members keep the tables' names, so the rest of the text is the same.
struct GlslText {
  std::string text, buffered;
  std::vector<int> block;  // std430: the int arrays tightly packed, in the order declared
};

// `banner` opens the text, `cost_lines` are the "//" lines of the C++ header's counts. float,
// vecN, matN, or with `double_precision` double, dvecN, dmatN.
GlslText glsl_evaluator(const Derivation& a, const std::string& banner, const std::string& name,
                        const std::vector<OrbitCode>& orbits,
                        const std::vector<std::string>& cost_lines, bool double_precision);

}  // namespace boxgen::generator
