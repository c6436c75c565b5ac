// The command-line conventions boxgen and boxrecon share: a usage error is one line on stderr
// with exit code 2, and a failed write to stdout (full disk, closed pipe) turns success into
// exit code 1, never a silent success with truncated output.
#pragma once
#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>
#include <optional>
#include <string>

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

// Output goes through both iostreams and stdio (fmt): both are flushed and checked.
inline int finish(int code, const char* program) {
  std::cout.flush();
  const bool failed = !std::cout || std::fflush(stdout) != 0 || std::ferror(stdout);
  if (failed && code == 0) {
    std::cerr << program << ": error: could not write the output (disk full or closed pipe?)\n";
    return 1;
  }
  return code;
}

}  // namespace boxgen::app
