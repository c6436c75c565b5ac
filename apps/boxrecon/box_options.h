// The box a command works in (resample, render, compare), in world coordinates: `--box LO HI`
// or `--min X Y Z --max X Y Z`. Both spellings fill one BoxOptions, so the commands read one
// thing and check it in one place.
#pragma once
#include <CLI/CLI.hpp>

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "runtime/resample.h"

namespace boxgen::app {

struct BoxOptions {
  std::vector<double> min, max;  // both empty, or three coordinates each
};

// Adds --min, --max (each X Y Z, the two together) and --box LO HI (LO and HI each one number
// for all three axes or three comma-separated ones, "x,y,z"), exclusive; `what` ends the help of
// --box (what the box is and its default). Returns the three options, for further exclusions.
std::array<CLI::Option*, 3> add_box_options(CLI::App* command, BoxOptions& options,
                                            const std::string& what);

// One corner of --box: "c" (c, c, c) or "x,y,z", each finite; nothing for any other text.
std::optional<std::array<double, 3>> parse_box_corner(std::string_view text);

// The box given, unchecked (nothing without --box or --min/--max).
std::optional<runtime::Box> given_box(const BoxOptions& options);

// The box given (compare and render): finite, min <= max on each axis, and inside `region`
// (default_box of the coefficients: where the filter reconstructs); else std::invalid_argument or
// std::out_of_range, one line naming the region.
runtime::Box box_from_options(const BoxOptions& options, const runtime::Box& region,
                              const std::string& filter_name);

}  // namespace boxgen::app
