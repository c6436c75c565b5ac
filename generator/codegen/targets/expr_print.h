// The print pass of the expression graph: one scheduled program
// (generator/codegen/ir/expr_schedule.h) written through a target's printer
// (generator/codegen/targets/target_printer.h: its literals and declarations), as GiNaC prints one
// expression in several print contexts. The C++ and CUDA evaluators use the template orbit
// function's body; GLSL, without templates, gets one function per path. Every operation counted by
// the schedule is written exactly once.
#pragma once
#include <string>

#include "generator/codegen/ir/expr_schedule.h"

namespace boxgen::generator {

class TargetPrinter;

// The expression of `id` with its temporaries named and the rest inline.
std::string print_expression(const expr::Program& p, expr::NodeId id, const TargetPrinter& t);

// The body of `template <int Order, class T> T orbit_k(const T* v, const T* x, T* d)`: the value
// block, then the gradient block under `if constexpr (Order >= 1)` and the Hessian block nested in
// it under `if constexpr (Order >= 2)`.
std::string print_cpp_body(const expr::Program& p, const TargetPrinter& t);

// The statements of the paths up to `order` (0, 1, 2), d[i] assigned, ending in
// "return <value>;", each line indented by `indent`.
std::string print_straight_line(const expr::Program& p, int order, const TargetPrinter& t,
                                const std::string& indent);

}  // namespace boxgen::generator
