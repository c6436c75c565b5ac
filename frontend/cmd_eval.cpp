#include <fmt/core.h>

#include "frontend/commands.h"
#include "frontend/progress.h"
#include "generator/error.h"
#include "generator/piece_checks.h"
#include "generator/piecewise_form.h"

namespace boxgen::frontend {

namespace {
constexpr long kMaxEvalCoordinate =
    1000000;  // far beyond any support (entries <= 64, <= 32 columns)
}  // namespace

nlohmann::json eval_json(const Common& c, const std::vector<std::string>& points,
                         const std::string& derivative) {
  const BoxSplineSpec spec = parse_spec(c.spec, c.lattice);
  const int n = spec.dimension();
  std::array<int, 3> orders{0, 0, 0};
  if (!derivative.empty()) {
    const RatVec d = parse_point(derivative, n, "--derivative orders");
    for (int i = 0; i < n; ++i) {
      if (!is_integer(d[i]) || cln::minusp(d[i]) || d[i] > 64)
        fail_input("--derivative orders must be integers from 0 to 64, got '" + derivative + "'");
      orders[i] = static_cast<int>(floor_to_int64(d[i]));
    }
  }
  std::vector<RatVec> xs;
  for (const auto& p : points) {
    xs.push_back(parse_point(p, n, "point"));
    // Cells are keyed by 32-bit levels of nu . x: refuse what that frame cannot hold.
    for (const auto& v : xs.back())
      if (cln::abs(v) > Rational(kMaxEvalCoordinate))
        fail_input(fmt::format(
            "point '{}' has a coordinate too large for the exact frame: coordinates must be at "
            "most {} in magnitude",
            p, kMaxEvalCoordinate));
  }
  ProgressPrinter progress(false);  // on a terminal, for derivations beyond two seconds
  const PiecewiseForm form = derive_piecewise(spec, DerivationMethod::TruncatedPower,
                                              progress.callback(), derivation_budget(c));
  progress.finish();
  const RatVec centre = spline_centre(spec);
  const Rational scale = Rational(spec.lattice.det_abs());
  nlohmann::json out = nlohmann::json::array();
  std::vector<Rational> values;
  for (const auto& x : xs) {
    RatVec u = x;  // M(x) = |det G| M_Xi(x + c)
    for (int i = 0; i < n; ++i) u[i] = u[i] + centre[i];
    values.push_back(form.value_at(u, orders) * scale);
  }
  for (size_t k = 0; k < xs.size(); ++k)
    out.push_back({{"x", rational_list(xs[k])},
                   {"derivative", std::vector<int>(orders.begin(), orders.begin() + n)},
                   {"value", to_string(values[k])},
                   {"value_float", to_double(values[k])}});
  return out;
}

int run_eval(const Common& c, const std::vector<std::string>& points,
             const std::string& derivative) {
  const nlohmann::json out = eval_json(c, points, derivative);
  if (c.json) {
    print_json(out);
  } else {
    for (const auto& point : out) fmt::print("{}\n", point["value"].get<std::string>());
  }
  return 0;
}

}  // namespace boxgen::frontend
