// Points to evaluate at, as text: one point "x y z" (world coordinates) per line.
//
// What a user's file may hold besides: blank lines, comments from '#' to the end of the line, a
// leading '+' on a number, Windows line ends (CRLF) and a UTF-8 byte order mark at the start.
// Numbers are C's decimal or hexadecimal floating-point forms and must be finite. The path "-"
// reads standard input; a directory, a missing file or an unreadable one is an error. Lines are
// read as they arrive: a line longer than kMaxPointsLineBytes or more than max_points() points is
// an error (so /dev/zero or an endless stream is refused, not read until memory runs out).
#pragma once
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "runtime/lattice_volume.h"

namespace boxgen::runtime {

inline constexpr std::size_t kMaxPointsLineBytes = 4096;
// 10^8 points: 2.4 GB as coordinates, before any value is computed.
inline constexpr std::size_t kMaxPoints = 100'000'000;
// The bytes a point may take while it is read and evaluated: its coordinates three times over
// (a growing vector's old and new storage) and its results (value, gradient, Hessian).
inline constexpr std::size_t kBytesPerPoint = 128;
// The most points a file may hold here: kMaxPoints, or fewer when the memory this process may
// still take (support/available_memory.h) holds fewer of kBytesPerPoint.
std::size_t max_points();

// The points of `text`; `name` (the file name) starts each error message. Throws
// std::invalid_argument "name:line: ..." (one line) for a line that is not three finite numbers.
std::vector<Vec3> parse_points(std::string_view text, std::string_view name);

// The points of everything readable from `fd` until its end, parsed line by line as it arrives
// (a pipe, a terminal, a file); `name` starts each error message. Throws as parse_points, and
// std::invalid_argument if reading fails.
std::vector<Vec3> read_points_stream(int fd, std::string_view name);

// parse_points of the file's contents ("-": standard input). Throws std::invalid_argument (one
// line, naming the file) if it cannot be read or parsed.
std::vector<Vec3> read_points_file(const std::string& path);

}  // namespace boxgen::runtime
