// `boxgen emit --name` accepted names that do not compile (MAXFLOAT, RAND_MAX,
// EXIT_SUCCESS and Traits on their own; FLT_MAX, DBL_MAX, CHAR_BIT, BUFSIZ beside the usual
// headers; GLSL's reserved gl_ prefix), and refused a name over 64 characters only after the
// derivation, as "not an identifier". The macros are read from this machine's compiler, not
// from a list of ours: every one it defines after the usual headers must be refused.
#include "generator/codegen/evaluator_name.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <set>
#include <string>

#include "generator/error.h"

namespace boxgen::generator {
namespace {

std::string refusal(const std::string& name) {
  try {
    check_evaluator_name(name);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// The macros `c++ -dM -E` defines after the C and C++ headers a user includes beside an
// evaluator, less those already reserved to the implementation ('_' first, or '__').
std::set<std::string> macros_of_the_usual_headers() {
  std::string includes;
  for (const char* h : {"array", "cassert", "cerrno", "cfloat", "cinttypes", "climits", "cmath",
                        "csignal", "cstddef", "cstdint", "cstdio", "cstdlib", "cstring", "ctime"})
    includes += std::string("#include <") + h + ">\\n";
  std::set<std::string> names;
  FILE* pipe = ::popen(("printf '" + includes + "' | c++ -x c++ -std=c++20 -dM -E -").c_str(), "r");
  if (!pipe) return names;
  char line[4096];
  while (std::fgets(line, sizeof line, pipe)) {
    const std::string text(line);
    if (text.rfind("#define ", 0) != 0) continue;
    const std::string name = text.substr(8, text.find_first_of(" (\n", 8) - 8);
    if (name[0] != '_' && name.find("__") == std::string::npos) names.insert(name);
  }
  ::pclose(pipe);
  return names;
}

TEST(EvaluatorName, EveryMacroOfTheUsualHeadersIsRefused) {
  const std::set<std::string> macros = macros_of_the_usual_headers();
  ASSERT_GT(macros.size(), 100u) << "c++ -dM -E gave too few macros: is c++ installed?";
  for (const char* m : {"FLT_MAX", "DBL_MAX", "CHAR_BIT", "BUFSIZ", "RAND_MAX", "EXIT_SUCCESS",
                        "MAXFLOAT", "stdin", "errno"})
    EXPECT_TRUE(macros.count(m)) << m << " is not among the compiler's macros";
  for (const std::string& m : macros) EXPECT_NE(refusal(m), "") << m << " was accepted";
}

TEST(EvaluatorName, NamesOfTheEmittedCodeAndGlslReservedNamesAreRefused) {
  for (const char* name : {"Traits", "Located", "kLattice", "kCentre", "locate", "evaluate",
                           "detail", "std", "registry"})
    EXPECT_NE(refusal(name).find("taken"), std::string::npos) << name;
  EXPECT_NE(refusal("gl_spline").find("'gl_', reserved in GLSL"), std::string::npos);
  EXPECT_NE(refusal("M7").find("lowercase"), std::string::npos);
}

TEST(EvaluatorName, OverLongNamesAreRefusedForTheirLength) {
  EXPECT_EQ(refusal(std::string(64, 'a')), "");
  EXPECT_NE(refusal(std::string(65, 'a')).find("has 65 characters, more than the 64 allowed"),
            std::string::npos)
      << refusal(std::string(65, 'a'));
}

TEST(EvaluatorName, OrdinaryNamesAreAccepted) {
  for (const char* name : {"m7", "cart7", "zp_data", "spec_0123456789abcdef", "my_spline",
                           "Quartic7", "hex3", "m7_bcc", "x1"})
    EXPECT_EQ(refusal(name), "") << name;
}

}  // namespace
}  // namespace boxgen::generator
