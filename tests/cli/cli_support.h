// Shared helpers for the CLI tests: run the real boxgen binary, parse its JSON, and do exact
// rational arithmetic (CLN) on the "p/q" strings it prints. Expected values in the tests are
// derived by hand (see each test's comment), never copied from boxgen's own output.
#pragma once
#include <gtest/gtest.h>

#include <cln/rational.h>
#include <cln/rational_io.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "run_process.h"

#ifndef BOXGEN_EXE
#error "BOXGEN_EXE must name the boxgen binary (set by tests/cli/CMakeLists.txt)"
#endif
#ifndef BOXRECON_EXE
#error "BOXRECON_EXE must name the boxrecon binary (set by tests/cli/CMakeLists.txt)"
#endif

namespace boxgen::test {

// boxrecon's `cubic` test function (runtime/test_functions.cpp) and its gradient, written out
// here again so that the CLI tests check the program against an independent formula.
inline double cubic(const std::array<double, 3>& p) {
  return p[0] * p[0] * p[0] - 2 * p[0] * p[1] * p[2] + 3 * p[1] * p[1] - p[2] + 1;
}
inline std::array<double, 3> cubic_gradient(const std::array<double, 3>& p) {
  return {3 * p[0] * p[0] - 2 * p[1] * p[2], -2 * p[0] * p[2] + 6 * p[1], -2 * p[0] * p[1] - 1};
}

// Sanitizer builds run the derivations several times slower; the deadline only has to catch hangs.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr int kSlowdown = 10;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr int kSlowdown = 10;
#else
inline constexpr int kSlowdown = 1;
#endif
#else
inline constexpr int kSlowdown = 1;
#endif
// AddressSanitizer reserves terabytes of shadow address space at start-up, so its programs cannot
// run under an address-space limit (ulimit -v) at all.
inline constexpr bool kAddressSanitizer = kSlowdown > 1;

// A release build derives M7 with its checks in about 4 s and runs table1 in about 7 s on the
// 2-core development machine: 120 s leaves room for a loaded machine and still catches a hang.
inline constexpr std::chrono::seconds kDefaultTimeout{120 * kSlowdown};

inline ProcessResult boxgen(const std::vector<std::string>& args,
                            std::chrono::seconds timeout = kDefaultTimeout) {
  return run_process(BOXGEN_EXE, args, timeout);
}

// Where a boxrecon run reads stdin and writes stdout ("": /dev/null and the captured `out`).
struct Redirect {
  std::string stdout_file;
  std::string stdin_file;
};

// Runs boxrecon: this build's, or the one BOXRECON_UNDER_TEST names (a sanitized or installed
// build, or an older one to show that a test fails on it). Some failing NRRD reads leak inside
// Teem; a sanitized boxrecon suppresses those itself (support/lsan_suppressions.cpp), so its
// stderr stays one line.
inline ProcessResult boxrecon(const std::vector<std::string>& args, const Redirect& io = {},
                              std::chrono::seconds timeout = std::chrono::seconds(60 * kSlowdown)) {
  const char* other = std::getenv("BOXRECON_UNDER_TEST");
  return run_process(other && *other ? other : BOXRECON_EXE, args, timeout, io.stdout_file,
                     io.stdin_file);
}

// Case-insensitive matching of messages.
inline std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// Runs a command that must succeed: exit 0, nothing on stderr. Returns stdout.
inline std::string boxgen_ok(const std::vector<std::string>& args) {
  const ProcessResult r = boxgen(args);
  EXPECT_TRUE(r.exited && r.exit_code == 0 && !r.timed_out) << describe(args, r);
  EXPECT_EQ(r.err, "") << describe(args, r);
  return r.out;
}

// The same for boxrecon.
inline std::string boxrecon_ok(const std::vector<std::string>& args) {
  const ProcessResult r = boxrecon(args);
  EXPECT_TRUE(r.exited && r.exit_code == 0 && !r.timed_out) << describe(args, r);
  EXPECT_EQ(r.err, "") << describe(args, r);
  return r.out;
}

// A whole file's bytes, and a file written from bytes (volumes and images the tests inspect or
// plant by hand).
inline std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}
inline void write_bytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// Runs a command that must succeed and print one JSON document.
inline nlohmann::json boxgen_json(const std::vector<std::string>& args) {
  const std::string out = boxgen_ok(args);
  try {
    return nlohmann::json::parse(out);
  } catch (const nlohmann::json::exception& e) {
    ADD_FAILURE() << "stdout is not JSON (" << e.what() << ")\n" << out.substr(0, 2000);
    return nlohmann::json();
  }
}

using Q = cln::cl_RA;

inline std::string str(const Q& q) {
  std::ostringstream s;
  s << q;
  return s.str();
}

// Parses an exact value as boxgen prints it: "n", "-n" or "p/q" in lowest terms with q > 1.
// Anything else (a decimal, "2/4", "+3", "1/1") is not the canonical exact form and is rejected.
inline std::optional<Q> parse_exact(const std::string& text) {
  static const std::regex form("-?(0|[1-9][0-9]*)(/[1-9][0-9]*)?");
  if (!std::regex_match(text, form)) return std::nullopt;
  const Q q(text.c_str());
  if (str(q) != text) return std::nullopt;  // not in lowest terms
  return q;
}

// The exact value of a JSON string field; a failure when it is missing or not canonical.
inline Q exact(const nlohmann::json& j) {
  if (!j.is_string()) {
    ADD_FAILURE() << "expected an exact value as a string \"p/q\", got " << j.dump();
    return Q(0);
  }
  const auto q = parse_exact(j.get<std::string>());
  if (!q) ADD_FAILURE() << "not a canonical exact rational: " << j.dump();
  return q.value_or(Q(0));
}

}  // namespace boxgen::test
