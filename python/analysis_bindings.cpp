// boxgen.analyze, pieces, prefilter, metrics, kernel, spectrum: the JSON the boxgen commands
// print with --json (frontend/commands.h builds it; nothing is rebuilt here), as Python dicts,
// with the sampled curves of kernel and spectrum as NumPy arrays. The derivations run without the
// GIL.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "frontend/commands.h"
#include "python/bindings.h"

namespace py = pybind11;

namespace boxgen::python {

py::object to_python(const nlohmann::json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::object: {
      py::dict d;
      for (const auto& [key, value] : j.items()) d[py::str(key)] = to_python(value);
      return d;
    }
    case nlohmann::json::value_t::array: {
      py::list l;
      for (const auto& value : j) l.append(to_python(value));
      return l;
    }
    case nlohmann::json::value_t::string:
      return py::str(j.get<std::string>());
    case nlohmann::json::value_t::boolean:
      return py::bool_(j.get<bool>());
    case nlohmann::json::value_t::number_integer:
      return py::int_(j.get<std::int64_t>());
    case nlohmann::json::value_t::number_unsigned:
      return py::int_(j.get<std::uint64_t>());
    case nlohmann::json::value_t::number_float:
      return py::float_(j.get<double>());
    default:
      return py::none();
  }
}

namespace {

using Specs = std::variant<std::string, std::vector<std::string>>;

std::vector<std::string> spec_list(const Specs& specs) {
  if (const auto* one = std::get_if<std::string>(&specs)) return {*one};
  const auto& many = std::get<std::vector<std::string>>(specs);
  if (many.empty()) throw py::value_error("give at least one SPEC");
  return many;
}

frontend::Common common(const std::string& spec, const std::optional<std::string>& lattice) {
  frontend::Common c;
  c.spec = spec;
  c.lattice = lattice.value_or("");
  c.json = true;
  return c;
}

// The JSON of `build` computed without the GIL, then converted with it.
template <class Build>
py::object json_result(Build&& build) {
  nlohmann::json j;
  {
    py::gil_scoped_release release;
    j = build();
  }
  return to_python(j);
}

// The keys holding sampled curves become float64 arrays, at the top level and one level down
// (one entry per SPEC).
py::object with_arrays(py::object result, const std::vector<std::string>& keys) {
  auto convert = [&](const py::dict& d) {
    for (const auto& key : keys)
      if (d.contains(key)) d[py::str(key)] = py::array_t<double>(d[py::str(key)]);
  };
  py::dict top = result.cast<py::dict>();
  convert(top);
  for (auto item : top)
    if (py::isinstance<py::dict>(item.second)) convert(item.second.cast<py::dict>());
  return result;
}

// The SPECs (each SPEC or SPEC@LATTICE), the default lattice and the labels (one per SPEC).
frontend::FrequencyOptions spec_options(const Specs& specs,
                                        const std::optional<std::string>& lattice,
                                        const std::optional<std::vector<std::string>>& labels) {
  frontend::FrequencyOptions o;
  o.specs = spec_list(specs);
  o.lattice = lattice.value_or("");
  o.labels = labels.value_or(std::vector<std::string>{});
  o.json = true;
  return o;
}

// With --w LIST or --from/--to/--steps.
frontend::FrequencyOptions frequency_options(const Specs& specs,
                                             const std::optional<std::string>& lattice,
                                             const std::optional<std::vector<std::string>>& labels,
                                             const std::optional<std::vector<double>>& w,
                                             std::optional<double> w_from,
                                             std::optional<double> w_to, int steps) {
  frontend::FrequencyOptions o = spec_options(specs, lattice, labels);
  if (w) o.w = *w;
  o.from = w_from;
  o.to = w_to;
  o.steps = steps;
  return o;
}

std::string shells_text(const std::variant<std::string, std::vector<int>>& shells) {
  if (const auto* text = std::get_if<std::string>(&shells)) return *text;
  std::string out;
  for (int s : std::get<std::vector<int>>(shells))
    out += (out.empty() ? "" : ",") + std::to_string(s);
  return out;
}

}  // namespace

void bind_analysis(py::module_& m) {
  m.def(
      "_eval_json",
      [](const std::string& spec, const std::vector<std::string>& points,
         const std::string& derivative, const std::optional<std::string>& lattice) {
        if (points.empty()) throw py::value_error("eval: give at least one point");
        return json_result(
            [&] { return frontend::eval_json(common(spec, lattice), points, derivative); });
      },
      py::arg("spec"), py::arg("points"), py::arg("derivative") = "",
      py::arg("lattice") = py::none(),
      "`boxgen eval SPEC --at POINT... --json` as a list of dicts (boxgen.eval converts it).");
  m.def(
      "emit",
      [](const std::string& spec, const std::string& name,
         const std::optional<std::string>& lattice, const std::string& target,
         const std::string& precision, const std::string& strategy,
         const std::optional<std::variant<std::string, std::vector<int>>>& shells) {
        const frontend::EmitLanguage language{target, precision,
                                              shells ? shells_text(*shells) : ""};
        std::vector<generator::EmittedFile> files;
        {
          py::gil_scoped_release release;
          files = frontend::emit_evaluator(common(spec, lattice), name, strategy, language);
        }
        py::dict out;
        for (const auto& f : files) out[py::str(f.filename)] = py::str(f.text);
        return out;
      },
      py::arg("spec"), py::arg("name"), py::arg("lattice") = py::none(), py::arg("target") = "cpp",
      py::arg("precision") = "float", py::arg("strategy") = "auto", py::arg("shells") = py::none(),
      "The files `boxgen emit SPEC --name NAME --out DIR` writes, {file name: text}, byte for "
      "byte (target: cpp | glsl | cuda; precision: float | double, glsl only; strategy: auto | "
      "horner | shifted | bernstein | separable | monomial; shells: q1's shells, \"0,1\" or [0, "
      "1]).");
  m.def(
      "bbform",
      [](const std::string& spec, const std::optional<std::string>& lattice,
         const std::variant<int, std::string>& region) {
        const std::string r = std::holds_alternative<int>(region)
                                  ? std::to_string(std::get<int>(region))
                                  : std::get<std::string>(region);
        return json_result([&] { return frontend::bbform_output(common(spec, lattice), r).json; });
      },
      py::arg("spec"), py::arg("lattice") = py::none(), py::arg("region") = "reference",
      "The BB-coefficients of `boxgen bbform SPEC --json` (region: \"reference\", every reference "
      "region, or an orbit's index), as a dict.");
  m.def(
      "analyze",
      [](const std::string& spec, const std::optional<std::string>& lattice,
         const std::string& checks) {
        frontend::AnalyzeOptions o;
        o.checks = checks;
        return json_result([&] {
          return frontend::analyze_json(frontend::analyze_derivation(common(spec, lattice), o, {}));
        });
      },
      py::arg("spec"), py::arg("lattice") = py::none(), py::arg("checks") = "default",
      "Everything `boxgen analyze SPEC --json` derives, as a dict.");
  m.def(
      "pieces",
      [](const std::string& spec, const std::optional<std::string>& lattice, const std::string& of,
         const std::string& region) {
        return json_result([&] {
          return nlohmann::json::parse(
              frontend::pieces_text(common(spec, lattice), of, region, "json"));
        });
      },
      py::arg("spec"), py::arg("lattice") = py::none(), py::arg("of") = "spline",
      py::arg("region") = "reference",
      "The piecewise polynomials of `boxgen pieces SPEC --json` (of: spline | filter; region: "
      "reference | all | an index), as a dict.");
  m.def(
      "prefilter",
      [](const std::string& spec,
         const std::optional<std::variant<std::string, std::vector<int>>>& shells,
         const std::optional<std::string>& lattice, const std::optional<std::string>& prefilter) {
        const std::string text = shells ? shells_text(*shells) : "";
        const std::string name = prefilter.value_or("");
        if (text.empty() == name.empty())
          throw py::value_error("prefilter: give either shells or prefilter");
        return json_result(
            [&] { return frontend::prefilter_json(common(spec, lattice), text, name); });
      },
      py::arg("spec"), py::arg("shells") = py::none(), py::arg("lattice") = py::none(),
      py::arg("prefilter") = py::none(),
      "The exact prefilter of `boxgen prefilter SPEC --shells 0,1 --json` (shells: \"0,1\" or "
      "[0, 1]) or of `--prefilter NAME` (q1, q2, q1opt, q2opt, qfir:K), as a dict.");
  m.def(
      "metrics",
      [](const Specs& specs, const std::optional<std::string>& lattice,
         const std::optional<std::vector<std::string>>& labels, bool equal_density) {
        frontend::FrequencyOptions o = spec_options(specs, lattice, labels);
        o.equal_density = equal_density;
        return json_result([&] { return frontend::metrics_json(o); });
      },
      py::arg("specs"), py::arg("lattice") = py::none(), py::arg("labels") = py::none(),
      py::arg("equal_density") = false,
      "`boxgen metrics SPEC... --json`: smoothing and postaliasing per SPEC (each SPEC or "
      "SPEC@LATTICE), a dict keyed by SPEC or by its label.");
  m.def(
      "kernel",
      [](const Specs& specs, const std::optional<std::string>& lattice,
         const std::string& prefilter, const std::optional<std::string>& direction,
         const std::optional<std::vector<double>>& w, std::optional<double> w_from,
         std::optional<double> w_to, int steps,
         const std::optional<std::vector<std::string>>& labels, bool equal_density) {
        frontend::FrequencyOptions o =
            frequency_options(specs, lattice, labels, w, w_from, w_to, steps);
        o.equal_density = equal_density;
        o.prefilter = prefilter;
        o.direction = direction.value_or("");
        return with_arrays(json_result([&] { return frontend::kernel_json(o); }), {"w", "E"});
      },
      py::arg("specs"), py::arg("lattice") = py::none(), py::arg("prefilter") = "q2",
      py::arg("direction") = py::none(), py::arg("w") = py::none(), py::arg("w_from") = py::none(),
      py::arg("w_to") = py::none(), py::arg("steps") = 0, py::arg("labels") = py::none(),
      py::arg("equal_density") = false,
      "`boxgen kernel SPEC... --json`: the error kernel E(w d) at w (or w_from..w_to in steps "
      "points); {'w', 'E'} as NumPy arrays, keyed by SPEC (or label) when there are several.");
  m.def(
      "spectrum",
      [](const Specs& specs, const std::string& line, const std::optional<std::string>& lattice,
         const std::optional<std::vector<double>>& w, std::optional<double> w_from,
         std::optional<double> w_to, int steps,
         const std::optional<std::vector<std::string>>& labels, bool equal_density) {
        frontend::FrequencyOptions o =
            frequency_options(specs, lattice, labels, w, w_from, w_to, steps);
        o.equal_density = equal_density;
        o.line = line;
        return with_arrays(json_result([&] { return frontend::spectrum_json(o); }),
                           {"w", "magnitude"});
      },
      py::arg("specs"), py::arg("line"), py::arg("lattice") = py::none(), py::arg("w") = py::none(),
      py::arg("w_from") = py::none(), py::arg("w_to") = py::none(), py::arg("steps") = 0,
      py::arg("labels") = py::none(), py::arg("equal_density") = false,
      "`boxgen spectrum SPEC... --line a,b,c --json`: |psi_hat(w d)| and the Nyquist interval of "
      "each SPEC's lattice; {'w', 'magnitude'} as NumPy arrays, keyed by SPEC (or label) when "
      "there are several.");
}

}  // namespace boxgen::python
