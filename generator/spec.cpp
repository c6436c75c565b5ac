#include "generator/spec.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <numeric>
#include <optional>

#include "generator/error.h"
#include "generator/int_linalg.h"
#include "support/lattice_text.h"

namespace boxgen::generator {

namespace {

// Limits that keep a derivation feasible; beyond them we refuse instead of running for hours.
constexpr std::int64_t kMaxComponent = 64;            // |xi_k[i]|
constexpr std::int64_t kMaxLatticeEntry = 1000;       // |G_ij|, as enforced by Lattice
constexpr std::int64_t kMaxSupportCells = 2'000'000;  // unit cells in the support's bounding box

using IntRows = std::vector<IntVec>;
using support::echo;
using support::is_blank;
using support::lower;
using support::trim;

// The shared parser's rows (support/lattice_text.h), its TextError an InputError.
template <class Parse>
auto parsed(Parse parse) {
  try {
    return parse();
  } catch (const support::TextError& e) {
    fail_input(e.what());
  }
}

std::string join_row(const IntVec& v) {
  std::string out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i) out += ',';
    out += std::to_string(v[i]);
  }
  return out;
}

std::string rows_text(const IntRows& rows) {
  std::string out;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (i) out += "; ";
    out += join_row(rows[i]);
  }
  return out;
}

std::string preset_names() {
  std::string out;
  for (const auto& p : presets()) {
    if (!out.empty()) out += ", ";
    out += p.name;
  }
  return out;
}

std::string describe(const Lattice& lattice) {
  if (lattice.name() == "bcc") return "the bcc lattice (coordinates all even or all odd)";
  if (lattice.name() == "fcc") return "the fcc lattice (even coordinate sum)";
  if (lattice.name() == "cartesian") return "the cartesian lattice";
  return fmt::format("the lattice with generator rows '{}'", rows_text(lattice.generator_rows()));
}

const PresetInfo* find_preset(std::string_view name) {
  const std::string key = lower(name);
  for (const auto& p : presets())
    if (p.name == key) return &p;
  return nullptr;
}

void check_directions(const IntColumns& xi, int n) {
  for (std::size_t k = 0; k < xi.size(); ++k)
    if (std::all_of(xi[k].begin(), xi[k].end(), [](std::int64_t v) { return v == 0; }))
      fail_input(
          fmt::format("direction {} ({}) is the zero vector: every direction must be nonzero",
                      k + 1, join_row(xi[k])));
  if (int r = rank(xi, n); r < n) {
    // A user who wrote Xi by rows gets its transpose: say so when that would be a valid SPEC.
    std::string hint;
    const int m = static_cast<int>(xi.size());
    if (m == 2 || m == 3) {
      IntColumns transposed(static_cast<std::size_t>(n), IntVec(static_cast<std::size_t>(m)));
      for (int i = 0; i < n; ++i)
        for (int k = 0; k < m; ++k)
          transposed[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)] = xi[k][i];
      const bool nonzero = std::none_of(transposed.begin(), transposed.end(), [](const IntVec& c) {
        return std::all_of(c.begin(), c.end(), [](std::int64_t v) { return v == 0; });
      });
      if (nonzero && rank(transposed, m) == m) {
        std::vector<std::string> cols;
        for (const auto& c : transposed) cols.push_back(join_row(c));
        hint = fmt::format(
            "; a SPEC lists the directions (the columns of Xi), one per ';': if you wrote the rows "
            "of "
            "Xi, its transpose '{}' is a valid {}-D SPEC",
            fmt::join(cols, "; "), m);
      }
    }
    fail_input(fmt::format(
        "rank-deficient direction matrix: the {} directions span only {} dimension(s); {} linearly "
        "independent directions are needed in {}-D{}",
        xi.size(), r, n, n, hint));
  }
}

// The support Xi[0,1]^m has the bounding-box side sum_k |xi_k[i]| in coordinate i; stencils and
// fine cells grow with that box measured in units of k = common_scale(spec) (a scaled pair is
// derived as the reduced one, common_scale.h). Sides are <= 32 * 64, so no overflow.
void check_support_size(const BoxSplineSpec& spec) {
  const std::int64_t k = common_scale(spec);
  std::int64_t cells = 1;
  std::vector<std::int64_t> sides;
  for (int i = 0; i < spec.dimension(); ++i) {
    std::int64_t side = 0;
    for (const auto& c : spec.directions) side += std::llabs(c[static_cast<std::size_t>(i)]);
    cells *= side / k;
    sides.push_back(side);
  }
  if (cells > kMaxSupportCells)
    fail_input(fmt::format(
        "support too large to derive: its bounding box is {} = {} cells of side {}, more than the "
        "limit of {}",
        fmt::join(sides, " x "), cells, k, kMaxSupportCells));
}

}  // namespace

const std::vector<PresetInfo>& presets() {
  static const std::vector<PresetInfo> list = {
      {"m7", "1,1,1; 1,-1,-1; -1,1,-1; -1,-1,1; 2,0,0; 0,2,0; 0,0,2", "bcc",
       "quartic seven-direction box spline M7 on BCC (Kim 2013)"},
      {"m8", "1,1,1; 1,-1,-1; -1,1,-1; -1,-1,1; 1,1,1; 1,-1,-1; -1,1,-1; -1,-1,1", "bcc",
       "quintic eight-direction box spline M8 on BCC (Entezari et al. 2004/2008)"},
      {"m12",
       "2,0,0; 0,2,0; 0,0,2; 2,0,0; 0,2,0; 0,0,2; -2,0,0; 0,-2,0; 0,0,-2; -2,0,0; 0,-2,0; 0,0,-2",
       "bcc",
       "tricubic B-spline M12 on BCC: 12 directions, total degree 9 (Csebfalvi-Hadwiger; Kim "
       "2013)"},
      {"cart7", "1,0,0; 0,1,0; 0,0,1; 1,1,1; 1,1,-1; 1,-1,1; -1,1,1", "cartesian",
       "quartic seven-direction box spline on the Cartesian lattice (Peters; Entezari-Moeller "
       "2006)"},
      {"fcc6", "1,1,0; 1,-1,0; 1,0,1; 1,0,-1; 0,1,1; 0,1,-1", "fcc",
       "cubic six-direction box spline on FCC (Kim, Entezari, Peters 2008)"},
      {"tricubic",
       "1,0,0; 0,1,0; 0,0,1; 1,0,0; 0,1,0; 0,0,1; 1,0,0; 0,1,0; 0,0,1; 1,0,0; 0,1,0; 0,0,1",
       "cartesian",
       "tricubic B-spline [I I I I], tensor product of cubic B-splines on the Cartesian lattice"},
      {"hex3", "1,0; 0,1; 1,1", "cartesian",
       "linear three-direction box spline (Courant hat function) on Z^2"},
      {"zp", "1,0; 0,1; 1,1; -1,1", "cartesian", "quadratic C^1 Zwart-Powell element on Z^2"},
  };
  return list;
}

std::string one_line(std::string_view text) {
  std::string out;
  for (const char c : trim(text)) {
    if (!is_blank(c))
      out += c;
    else if (!out.empty() && out.back() != ' ')
      out += ' ';
  }
  return out;
}

std::string BoxSplineSpec::directions_text() const {
  std::string out;
  for (std::size_t k = 0; k < directions.size(); ++k) {
    if (k) out += "; ";
    out += join_row(directions[k]);
  }
  return out;
}

Lattice parse_lattice(std::string_view text, int dimension) {
  if (dimension != 2 && dimension != 3)
    fail_input(fmt::format("lattice dimension must be 2 or 3, got {}", dimension));
  const std::string because = fmt::format("the directions are {}-dimensional", dimension);
  const support::LatticeText lattice = parsed(
      [&] { return support::parse_lattice_text(text, dimension, because, kMaxLatticeEntry); });
  if (lattice.name == "cartesian") return Lattice::cartesian(dimension);
  if (lattice.name == "bcc") return Lattice::bcc();
  if (lattice.name == "fcc") return Lattice::fcc();
  // The user writes G by rows; Lattice takes its columns.
  const std::size_t n = lattice.rows.size();
  IntColumns columns(n, IntVec(n));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) columns[j][i] = lattice.rows[i][j];
  return Lattice("custom", std::move(columns));
}

BoxSplineSpec parse_spec(std::string_view spec, std::string_view lattice_text) {
  const std::string_view t = trim(spec);
  if (t.empty())
    fail_input(fmt::format(
        "empty SPEC: expected a preset name ({}) or a direction list such as '1,0; 0,1; 1,1'",
        preset_names()));

  std::string name = "custom";
  std::string_view directions_text = t;
  std::string_view default_lattice;
  // A name is a preset; text with ',' or ';' is a direction list even when an entry is not a
  // number ("nan,1; 0,1"), so the message names the bad entry instead of an unknown preset.
  const bool looks_like_a_list = t.find_first_of(",;") != std::string_view::npos;
  if (std::isalpha(static_cast<unsigned char>(t.front())) && !looks_like_a_list) {
    const PresetInfo* preset = find_preset(t);
    if (!preset)
      fail_input(
          fmt::format("unknown preset '{}': valid presets are {}; or give a direction list such as "
                      "'1,0; 0,1; 1,1'",
                      echo(t), preset_names()));
    name = preset->name;
    directions_text = preset->directions;
    default_lattice = preset->lattice;
  }

  const support::RowSyntax syntax{"SPEC", "direction", kMaxComponent, "to derive"};
  const IntRows directions = parsed([&] {
    return support::parse_rows(directions_text, syntax, static_cast<std::size_t>(kMaxDirections));
  });
  const int n = static_cast<int>(directions.front().size());
  check_directions(directions, n);

  const std::string_view chosen = trim(lattice_text).empty() ? default_lattice : lattice_text;
  Lattice lattice = chosen.empty() ? Lattice::cartesian(n) : parse_lattice(chosen, n);
  for (std::size_t k = 0; k < directions.size(); ++k)
    if (!lattice.contains(directions[k]))
      fail_input(fmt::format(
          "direction {} ({}) is not a point of {}: every direction must lie in the lattice", k + 1,
          join_row(directions[k]), describe(lattice)));
  BoxSplineSpec out{name, std::string(spec), directions, std::move(lattice)};
  check_support_size(out);
  return out;
}

std::int64_t common_scale(const BoxSplineSpec& spec) {
  std::int64_t k = 0;
  for (const auto& columns : {spec.directions, spec.lattice.generator()})
    for (const auto& column : columns)
      for (auto v : column) k = std::gcd(k, v);
  return k == 0 ? 1 : k;
}

}  // namespace boxgen::generator
