// Points to evaluate at, as text: one point "x y z" (world coordinates) per line.
//
// What a user's file may hold besides: blank lines, comments from '#' to the end of the line, a
// leading '+' on a number, Windows line ends (CRLF) and a UTF-8 byte order mark at the start.
// Numbers are C's decimal or hexadecimal floating-point forms and must be finite. The path "-"
// reads standard input; a directory, a missing file or an unreadable one is an error.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "runtime/lattice_volume.h"

namespace boxgen::runtime {

// The points of `text`; `name` (the file name) starts each error message. Throws
// std::invalid_argument "name:line: ..." (one line) for a line that is not three finite numbers.
std::vector<Vec3> parse_points(std::string_view text, std::string_view name);

// parse_points of the file's contents ("-": standard input). Throws std::invalid_argument (one
// line, naming the file) if it cannot be read or parsed.
std::vector<Vec3> read_points_file(const std::string& path);

}  // namespace boxgen::runtime
