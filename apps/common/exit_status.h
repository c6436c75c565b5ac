// The command-line conventions boxgen and boxrecon share: a usage error is one line on stderr
// with exit code 2, and a failed write to stdout (full disk, closed pipe) turns success into
// exit code 1, never a silent success with truncated output.
#pragma once
#include <poll.h>
#include <CLI/CLI.hpp>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>

namespace boxgen::app {

// Parses the command line. Returns an exit code when the program should stop here (--help or
// --version printed: 0; a usage error printed as one line: 2), nothing when it should go on.
inline std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv,
                                             const char* program) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string what = e.what();
    for (char& c : what)
      if (c == '\n') c = ' ';
    std::cerr << program << ": usage error: " << what << " (see " << program << " --help)\n";
    return 2;
  }
  return std::nullopt;
}

// Whether standard output is a pipe or socket whose reader has gone. errno cannot say so at the
// end: the write that met EPIPE may be long past (the stream then only remembers that it failed).
inline bool output_reader_gone() {
  pollfd out{1, POLLOUT, 0};
  return ::poll(&out, 1, 0) == 1 && (out.revents & (POLLERR | POLLHUP)) != 0;
}

// Output goes through both iostreams and stdio (fmt): both are flushed and checked. A reader
// that has gone (EPIPE: SIGPIPE is ignored, support::handle_signals) ends the program quietly
// with status 1, as `yes | head` ends; any other failure (a full disk) is one line and status 1.
inline int finish(int code, const char* program) {
  errno = 0;
  std::cout.flush();
  const bool failed = !std::cout || std::fflush(stdout) != 0 || std::ferror(stdout);
  if (failed && code == 0) {
    if (errno != EPIPE && !output_reader_gone())
      std::cerr << program << ": error: could not write the output: "
                << (errno != 0 ? std::strerror(errno) : "disk full or closed pipe?") << '\n';
    return 1;
  }
  return code;
}

// Option checks the two programs share (CLI11 validators): an option given with an unusable value
// is a usage error naming it, never a silent fall-back to the default.
inline const CLI::Validator kNonEmpty(
    [](std::string& text) {
      return text.empty() ? std::string("must not be empty") : std::string();
    },
    "NONEMPTY");
inline const CLI::Validator kFinitePositive(
    [](std::string& text) {
      double value = 0;
      std::size_t used = 0;
      try {
        value = std::stod(text, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != text.size() || !std::isfinite(value) || value <= 0)
        return "must be a finite number > 0, got '" + text.substr(0, 40) + "'";
      return std::string();
    },
    "NUMBER > 0");

// fmt::print reports a failed write to stdout as std::system_error: the same output error as
// finish() reports (quiet for a closed pipe), never an internal error.
inline bool is_output_error(const std::exception& e) {
  const auto* system = dynamic_cast<const std::system_error*>(&e);
  return system && system->code().category() == std::generic_category() &&
         std::string_view(system->what()).find("cannot write") != std::string_view::npos;
}
inline int report_output_error(const std::exception& e, const char* program) {
  const auto& system = dynamic_cast<const std::system_error&>(e);
  if (system.code().value() != EPIPE)
    std::cerr << program
              << ": error: could not write the output: " << std::strerror(system.code().value())
              << '\n';
  return 1;
}

}  // namespace boxgen::app
