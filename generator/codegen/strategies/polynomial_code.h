// The code of one orbit's reference polynomial (docs/design.md §11): the spline on the reference
// region is sum_k v[k] p_k(x) over its stencil, and a strategy decides how that sum and its exact
// derivatives are built into an expression graph (generator/codegen/ir/expr.h), shared between the
// value, the gradient and the Hessian; the counts of the scheduled graph let the emitter choose the
// cheapest strategy (`auto`) and are recorded in the header. The strategies build graphs only;
// each target's printer (generator/codegen/targets/target_printer.h) writes them. Each strategy is
// its own file, <name>_strategy.{h,cpp} beside this one, built with strategy_builders.h; this
// module names them and chooses between them.
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "generator/codegen/ir/expr_schedule.h"
#include "generator/spline_regions.h"

namespace boxgen::generator {

// `monomial`: one coefficient per monomial (a linear combination of the stencil values), then a
//   sum over a table of coordinate powers.
// `horner`: the same coefficients, stencil values grouped by shared weight, then nested Horner
//   forms of the polynomial and of each exact partial derivative.
// `shifted`: the Horner form in monomials of y = x - o about another exact origin o (the
//   centroid, a vertex or the midpoint of two vertices of the reference region, not 0), the one
//   with the fewest value + gradient operations; the coefficients are translated exactly.
// `bernstein`: on a simplicial reference region, the BB-coefficients (generator/bbform.h) as
//   linear combinations of the stencil values, the barycentric coordinates as exact affine forms
//   of x, de Casteljau's algorithm for the value and the gradient and Hessian from its last two
//   levels; it does not apply to other regions.
// `separable`: where every p_k is a product of univariate factors and the stencil splits into
//   full tensor grids (axis-aligned direction matrices: M12, tricubic), 1-D weights per axis
//   and a contraction per grid.
// `auto`: the cheapest of those that apply, by the value + gradient operation count.
enum class EmissionStrategy { Auto, Monomial, Horner, Separable, Shifted, Bernstein };

// "auto" | "monomial" | "horner" | "shifted" | "bernstein" | "separable"; anything else:
// InputError naming the choices.
EmissionStrategy parse_strategy(std::string_view name);
const char* strategy_name(EmissionStrategy s);

// The schedule's operation count (generator/codegen/ir/expr_schedule.h), which reports carry.
using expr::OperationCount;

struct StrategyCost {
  EmissionStrategy strategy = EmissionStrategy::Horner;
  OperationCount value, gradient, hessian;  // whole paths: value; value + gradient; + Hessian
};

// What an orbit's code computes, as data: a comment template (templates/orbit_<strategy>.fmt) and
// its named arguments; each target's printer writes it above the code (orbit_comment in
// generator/codegen/targets/target_printer.h).
struct OrbitComment {
  std::string_view format;  // a template of generator/embedded_templates.h
  std::vector<std::pair<const char*, std::string>> args;  // (name, value); names are literals
};

// The code of one orbit: its expression graph scheduled (generator/codegen/ir/expr_schedule.h),
// which every target's printer writes (C++: `template <int Order, class T> T orbit_<orbit>(const T*
// v, const T* x, T* d)`, support::evaluate_located describes d).
struct OrbitCode {
  EmissionStrategy strategy = EmissionStrategy::Horner;
  std::shared_ptr<const expr::Program> program;
  OrbitComment comment;                     // what the code computes
  OperationCount value, gradient, hessian;  // whole paths: value; value + gradient; + Hessian
  std::string form;  // what the strategy chose, for comments and reports ("about (1,1,1)"), or ""
  std::vector<StrategyCost> considered;  // auto: every applicable strategy, in the order tried
};

// Their report text (strategy_description, considered_text): generator/codegen/targets/
// emission_report.h.

// The code of one orbit in a given strategy (not Auto); nullopt when the strategy does not apply
// (separable code for a polynomial that is not a tensor product, bernstein code on a region that
// is not a simplex).
std::optional<OrbitCode> orbit_code(const ReferenceRegion& ref, int orbit, int n, int degree,
                                    EmissionStrategy strategy);

// Auto: every applicable strategy, the one with the fewest value + gradient operations (ties
// keep the earlier of horner, separable, monomial, shifted, bernstein). Otherwise the strategy
// asked for; InputError if it does not apply.
OrbitCode choose_orbit_code(const ReferenceRegion& ref, int orbit, int n, int degree,
                            EmissionStrategy strategy);

}  // namespace boxgen::generator
