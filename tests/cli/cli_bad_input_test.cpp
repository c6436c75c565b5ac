// Bad input through the real binary: every user mistake gets exactly one line on stderr that
// starts with "boxgen: ", a non-zero exit code that is not the internal-error code, nothing on
// stdout (no half-written answer), and no crash or hang.
#include <algorithm>
#include <cctype>

#include "cli_support.h"

namespace boxgen::test {
namespace {

constexpr int kInternalErrorCode = 3;  // apps/boxgen/main.cpp: 1 bad input, 2 bad usage, 3 internal

struct BadInput {
  const char* name;
  std::vector<std::string> args;
  // The message must name the culprit: at least one of these (case-insensitive) must appear.
  std::vector<std::string> mentions;
};

void PrintTo(const BadInput& c, std::ostream* os) { *os << c.name; }

// 33 directions spanning R^3 (e1, e2, e3 eleven times each), so the count is the only problem.
std::string directions_33() {
  std::string s;
  for (int i = 0; i < 11; ++i) s += i ? "; 1,0,0; 0,1,0; 0,0,1" : "1,0,0; 0,1,0; 0,0,1";
  return s;
}

std::vector<BadInput> bad_inputs() {
  return {
      // SPEC and lattice mistakes
      {"MalformedSpecText", {"analyze", "1,1,1; 1,x,1"}, {"'x'"}},
      {"ZeroMatrix", {"analyze", "0,0,0; 0,0,0; 0,0,0"}, {"zero"}},
      {"RankDeficientMatrix", {"analyze", "1,0,0; 2,0,0; 0,1,0"}, {"rank", "span", "dependent"}},
      {"DirectionNotInLattice",
       {"analyze", "1,0,0; 0,1,0; 0,0,1", "--lattice", "bcc"},
       {"lattice"}},
      {"SingularLattice",
       {"analyze", "1,0,0; 0,1,0; 0,0,1", "--lattice", "1,0,0; 0,1,0; 1,1,0"},
       {"singular", "determinant"}},
      {"MalformedLattice", {"analyze", "1,0; 0,1", "--lattice", "1,0; 0"}, {"lattice"}},
      {"LatticeOfWrongDimension", {"analyze", "1,0; 0,1", "--lattice", "bcc"}, {"dimension"}},
      {"MoreThan32Directions", {"analyze", directions_33()}, {"33", "32"}},
      {"MixedDimensions", {"analyze", "1,0; 0,1,1"}, {"dimension", "entries"}},
      {"EntryTooLarge",
       {"analyze", "99999999999999999999,0; 0,1"},
       {"99999999999999999999", "large"}},
      {"EmptySpec", {"analyze", ""}, {"spec"}},
      {"UnknownPreset", {"analyze", "m9"}, {"m9"}},
      {"UnknownPresetInEval", {"eval", "m9", "--at", "0 0 0"}, {"m9"}},
      // points
      {"NonNumericPoint", {"eval", "m7", "--at", "1 a 2"}, {"'a'"}},
      {"ZeroDenominatorInPoint", {"eval", "m7", "--at", "1/0 0 0"}, {"1/0"}},
      {"PointWithTooFewCoordinates", {"eval", "m7", "--at", "1 2"}, {"3"}},
      {"PointWithTooManyCoordinates", {"eval", "hex3", "--at", "1 2 3"}, {"2"}},
      {"EmptyPoint", {"eval", "m7", "--at", ""}, {"point", "coordinate"}},
      {"BadPointAfterGoodOne", {"eval", "m7", "--at", "0 0 0", "--at", "0 0 zero"}, {"zero"}},
      // usage
      {"UnknownSubcommand", {"frobnicate", "m7"}, {"unknown command 'frobnicate'"}},
      {"NoArguments", {}, {"subcommand"}},
      {"MissingSpec", {"analyze"}, {"spec"}},
      {"MissingAt", {"eval", "m7"}, {"--at"}},
      {"MissingAtValue", {"eval", "m7", "--at"}, {"--at"}},
      {"MissingShells", {"prefilter", "m7"}, {"--shells"}},
      {"UnknownOption", {"analyze", "m7", "--frob"}, {"--frob"}},
      // --shells
      {"ShellsWithoutOrigin", {"prefilter", "m7", "--shells", "1,2"}, {"0"}},
      {"ShellsTooFewForTheOrder", {"prefilter", "m7", "--shells", "0"}, {"order"}},
      {"ShellIndexOutOfRange", {"prefilter", "m7", "--shells", "0,9"}, {"9"}},
      {"ShellIndexNegative", {"prefilter", "m7", "--shells", "0,-1"}, {"-1"}},
      {"ShellIndexNotANumber", {"prefilter", "m7", "--shells", "0,x"}, {"x"}},
      {"ShellListedTwice", {"prefilter", "m7", "--shells", "0,1,1"}, {"twice", "1"}},
      {"ShellsAndANamedPrefilter",
       {"prefilter", "m7", "--shells", "0,1", "--prefilter", "q1"},
       {"--shells"}},
      {"UnknownNamedPrefilter", {"prefilter", "m7", "--prefilter", "q3"}, {"q3"}},
      {"FirTooFewShells", {"prefilter", "m7", "--prefilter", "qfir:0"}, {"qfir:1"}},
      {"FirShellOutOfRange", {"prefilter", "m7", "--prefilter", "qfir:9"}, {"qfir:9"}},
      {"FirShellNotANumber", {"prefilter", "m7", "--prefilter", "qfir:x"}, {"qfir:x"}},
      // --derivative
      {"DerivativeNotANumber", {"eval", "m7", "--at", "0 0 0", "--derivative", "1 x 0"}, {"x"}},
      {"DerivativeWrongCount",
       {"eval", "m7", "--at", "0 0 0", "--derivative", "1 0"},
       {"--derivative"}},
      {"DerivativeNegative",
       {"eval", "m7", "--at", "0 0 0", "--derivative", "-1 0 0"},
       {"--derivative"}},
      {"DerivativeFractional",
       {"eval", "m7", "--at", "0 0 0", "--derivative", "1/2 0 0"},
       {"--derivative"}},
      // d/dx of the hex3 hat at its peak: -1 on one side, 0 or 1 on others (cli_exactness_test.cpp)
      {"DerivativeAtAKink",
       {"eval", "hex3", "--at", "0 0", "--derivative", "1 0"},
       {"knot", "discontinuous"}},
      // --region
      {"RegionNotAnIndex", {"bbform", "m7", "--region", "foo"}, {"foo"}},
      {"RegionOutOfRange", {"bbform", "m7", "--region", "5"}, {"5"}},
      {"RegionNegative", {"bbform", "m7", "--region", "-1"}, {"-1"}},
      // --method
      {"UnknownAutocorrMethod", {"autocorr", "m7", "--method", "foo"}, {"foo"}},
      // emit (both fail before anything is derived or written)
      {"UnknownEmitStrategy",
       {"emit", "zp", "--name", "z", "--out", "/nonexistent/boxgen", "--strategy", "foo"},
       {"foo", "horner"}},
      // a form that does not apply to the filter's regions: one line naming why, nothing written
      {"EmitBernsteinOnCubes",
       {"emit", "m12", "--name", "z", "--out", "/nonexistent/boxgen", "--strategy", "bernstein"},
       {"bernstein", "not a simplex"}},
      {"EmitNameNotAnIdentifier",
       {"emit", "zp", "--name", "9z", "--out", "/nonexistent/boxgen"},
       {"9z"}},
      {"EmitNameWithAHyphen",
       {"emit", "zp", "--name", "my-spline", "--out", "/nonexistent/boxgen"},
       {"identifier"}},
      {"EmitNameIsAKeyword",
       {"emit", "zp", "--name", "namespace", "--out", "/nonexistent/boxgen"},
       {"keyword"}},
      // names that compile nowhere or clobber another file of the folder
      {"EmitNameShadowsStd", {"emit", "zp", "--name", "std", "--out", "/nonexistent/b"}, {"std"}},
      {"EmitNameIsTheRegistry",
       {"emit", "zp", "--name", "registry", "--out", "/nonexistent/b"},
       {"registry", "taken"}},
      {"EmitNameIsTheGlue",
       {"emit", "zp", "--name", "evaluator_support", "--out", "/nonexistent/b"},
       {"evaluator_support"}},
      {"EmitNameIsAPrefilterFile",
       {"emit", "zp", "--name", "m7_prefilters", "--out", "/nonexistent/b"},
       {"_prefilters"}},
      {"EmitNameIsAMacro", {"emit", "zp", "--name", "NULL", "--out", "/nonexistent/b"}, {"macro"}},
      {"EmitNameIsAnIntegerMacro",
       {"emit", "zp", "--name", "INT8_MAX", "--out", "/nonexistent/b"},
       {"macro"}},
      // names that were accepted and did not compile, or were refused late
      {"EmitNameIsMaxfloat",
       {"emit", "zp", "--name", "MAXFLOAT", "--out", "/nonexistent/b"},
       {"MAXFLOAT", "macro"}},
      {"EmitNameIsExitSuccess",
       {"emit", "zp", "--name", "EXIT_SUCCESS", "--out", "/nonexistent/b"},
       {"macro"}},
      {"EmitNameIsTraits",
       {"emit", "zp", "--name", "Traits", "--out", "/nonexistent/b"},
       {"Traits", "taken"}},
      {"EmitNameIsGlslReserved",
       {"emit", "zp", "--name", "gl_zp", "--out", "/nonexistent/b"},
       {"gl_", "GLSL"}},
      {"EmitNameIsTooLong",
       {"emit", "zp", "--name", std::string(65, 'z'), "--out", "/nonexistent/b"},
       {"65 characters", "64 allowed"}},
      {"EmitRegistryOfAnUnknownFilter",
       {"emit", "--registry", "nonexistent_filter", "--out", "/nonexistent/b"},
       {"nonexistent_filter"}},
      {"EmitRegistryListsAFilterTwice",
       {"emit", "zp", "--name", "h", "--registry", "h,h", "--out", "/nonexistent/b"},
       {"twice"}},
      {"EmitWithoutSpecOrRegistry", {"emit", "--out", "/nonexistent/b"}, {"--registry"}},
      {"EmitNameWithoutSpec", {"emit", "--name", "z", "--out", "/nonexistent/b"}, {"SPEC"}},
      // values that once fell back to a default in silence
      {"MaxSecondsNegative", {"analyze", "zp", "--max-seconds", "-5"}, {"--max-seconds"}},
      {"MaxSecondsNaN", {"analyze", "zp", "--max-seconds", "nan"}, {"--max-seconds", "nan"}},
      {"MaxSecondsEmpty", {"analyze", "zp", "--max-seconds", ""}, {"--max-seconds"}},
      {"MaxSecondsInfinite", {"analyze", "zp", "--max-seconds", "inf"}, {"--max-seconds"}},
      {"EmptyLattice", {"analyze", "zp", "--lattice", ""}, {"--lattice", "empty"}},
      {"EmptyLatticeOfAnalysis", {"metrics", "m7", "--lattice", ""}, {"--lattice", "empty"}},
      {"SpectrumSizeZero",
       {"spectrum", "m7", "--plane", "1,0,0", "--size", "0", "-o", "/nonexistent/b.png"},
       {"--size", "0"}},
      {"NotANumberInADirectionList", {"analyze", "nan,1; 0,1"}, {"not an integer"}},
      // the command-line conventions
      {"RankDeficientButTransposeValid",
       {"analyze", "1,0,1; 0,1,1"},
       {"transpose '1,0; 0,1; 1,1'"}},
      {"PointTooLargeForTheExactFrame", {"eval", "hex3", "--at", "1e30 0"}, {"too large"}},
      {"UnknownChecksMode", {"analyze", "zp", "--checks", "some"}, {"'some'"}},
      {"PredictedBeyondMaxSeconds",
       {"analyze", "m7", "--max-seconds", "0.000001"},
       {"--max-seconds"}},
  };
}

class BadInputTest : public ::testing::TestWithParam<BadInput> {};

TEST_P(BadInputTest, OneLineOnStderrNonZeroExitNothingOnStdout) {
  const BadInput& c = GetParam();
  const ProcessResult r = boxgen(c.args);
  const std::string what = describe(c.args, r);
  ASSERT_TRUE(r.started) << what;
  ASSERT_FALSE(r.timed_out) << "a bad input must not hang\n" << what;
  ASSERT_TRUE(r.exited) << "a bad input must not crash\n" << what;
  EXPECT_NE(r.exit_code, 0) << what;
  EXPECT_NE(r.exit_code, kInternalErrorCode) << "a user mistake is reported as an internal error\n"
                                             << what;
  EXPECT_EQ(r.out, "") << "nothing may be written to stdout on an error\n" << what;
  // Exactly one line: a single '\n', at the very end.
  ASSERT_FALSE(r.err.empty()) << what;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << what;
  EXPECT_EQ(r.err.back(), '\n') << what;
  EXPECT_EQ(r.err.rfind("boxgen: ", 0), 0u) << "stderr must start with 'boxgen: '\n" << what;
  const std::string message = lower(r.err);
  const bool named = std::any_of(c.mentions.begin(), c.mentions.end(), [&](const std::string& m) {
    return message.find(lower(m)) != std::string::npos;
  });
  EXPECT_TRUE(named) << "the message does not name the problem (expected one of: "
                     << ::testing::PrintToString(c.mentions) << ")\n"
                     << what;
}

INSTANTIATE_TEST_SUITE_P(Cli, BadInputTest, ::testing::ValuesIn(bad_inputs()),
                         [](const ::testing::TestParamInfo<BadInput>& param_info) {
                           return std::string(param_info.param.name);
                         });

}  // namespace
}  // namespace boxgen::test
