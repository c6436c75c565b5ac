#include "apps/boxrecon/box_options.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <system_error>

namespace boxgen::app {

using runtime::Box;

std::optional<std::array<double, 3>> parse_box_corner(std::string_view text) {
  std::array<double, 3> corner{};
  std::size_t count = 0;
  const char* at = text.data();
  const char* const end = text.data() + text.size();
  for (;;) {
    double value = 0;
    const auto [next, error] = std::from_chars(at, end, value);
    if (error != std::errc() || !std::isfinite(value)) return std::nullopt;
    corner[count++] = value;
    at = next;
    if (at == end) break;
    if (*at != ',' || count == 3) return std::nullopt;
    ++at;
  }
  if (count == 1) return std::array<double, 3>{corner[0], corner[0], corner[0]};
  if (count == 3) return corner;
  return std::nullopt;
}

std::array<CLI::Option*, 3> add_box_options(CLI::App* command, BoxOptions& options,
                                            const std::string& what) {
  auto* min = command->add_option("--min", options.min, "X Y Z: the box's lower corner (world)")
                  ->expected(3);
  auto* max = command->add_option("--max", options.max, "X Y Z: the box's upper corner (world)")
                  ->expected(3);
  const CLI::Validator corner(
      [](std::string& text) {
        return parse_box_corner(text)
                   ? std::string()
                   : "must be one finite number or three, x,y,z, got '" + text.substr(0, 40) + "'";
      },
      "X|X,Y,Z");
  auto* box = command
                  ->add_option_function<std::vector<std::string>>(
                      "--box",
                      [&options](const std::vector<std::string>& corners) {
                        const auto lo = parse_box_corner(corners.at(0));
                        const auto hi = parse_box_corner(corners.at(1));
                        options.min.assign(lo->begin(), lo->end());
                        options.max.assign(hi->begin(), hi->end());
                      },
                      "LO HI: the box (world), corners as X or X,Y,Z (one number: all three "
                      "axes), instead of --min/--max; " +
                          what)
                  ->expected(2)
                  ->check(corner);
  min->needs(max);
  max->needs(min);
  box->excludes(min)->excludes(max);
  return {min, max, box};
}

std::optional<Box> given_box(const BoxOptions& options) {
  if (options.min.size() != 3 || options.max.size() != 3) return std::nullopt;
  return Box{{options.min[0], options.min[1], options.min[2]},
             {options.max[0], options.max[1], options.max[2]}};
}

Box box_from_options(const BoxOptions& options, const Box& region, const std::string& filter_name) {
  const std::optional<Box> given = given_box(options);
  if (!given) return region;
  const Box& box = *given;
  for (int a = 0; a < 3; ++a) {
    if (!(std::isfinite(box.min[a]) && std::isfinite(box.max[a]) && box.min[a] <= box.max[a]))
      throw std::invalid_argument("the box's corners must be finite with min <= max on each axis");
    if (box.min[a] < region.min[a] || box.max[a] > region.max[a])
      throw std::out_of_range(
          fmt::format("the box leaves the region the {} filter reconstructs, [{:.9g}, {:.9g}] x "
                      "[{:.9g}, {:.9g}] x [{:.9g}, {:.9g}]",
                      filter_name, region.min[0], region.max[0], region.min[1], region.max[1],
                      region.min[2], region.max[2]));
  }
  return box;
}

}  // namespace boxgen::app
