// The CLI's conventions, as a new user meets them: --help says what a SPEC and --lattice list,
// --estimate predicts without deriving, the checks modes, eval --json records the derivative,
// and the prefilter summary names a shell only when all its taps carry the weight it claims.
#include <algorithm>
#include <array>
#include <cstdio>
#include <map>

#include "cli_support.h"

namespace boxgen::test {
namespace {

using nlohmann::json;

TEST(CliConventions, HelpSaysSpecListsColumnsAndLatticeTakesRows) {
  const std::string help = boxgen_ok({"analyze", "--help"});
  EXPECT_NE(help.find("COLUMNS of Xi"), std::string::npos) << help;
  EXPECT_NE(help.find("ROWS of G"), std::string::npos) << help;
  EXPECT_NE(help.find("--estimate"), std::string::npos) << help;
  EXPECT_NE(help.find("--max-seconds"), std::string::npos) << help;
  EXPECT_NE(help.find("--progress"), std::string::npos) << help;
  EXPECT_NE(help.find("--checks"), std::string::npos) << help;
}

TEST(CliConventions, EstimatePrintsPredictionWithoutDeriving) {
  const json e = boxgen_json({"analyze", "m7", "--estimate", "--json"});
  ASSERT_TRUE(e.contains("estimated_seconds")) << e.dump();
  ASSERT_TRUE(e.contains("estimated_bytes")) << e.dump();
  EXPECT_GT(e["estimated_seconds"].get<double>(), 0);
  EXPECT_GT(e["estimated_bytes"].get<double>(), 1e6);
  EXPECT_FALSE(e.contains("pieces")) << "--estimate must not derive";
  // The same estimate refuses up front only beyond the limit the user sets.
  const double predicted = e["estimated_seconds"].get<double>();
  const ProcessResult refused =
      boxgen({"analyze", "m7", "--max-seconds", std::to_string(predicted / 10)});
  EXPECT_EQ(refused.exit_code, 1) << describe({"analyze", "m7"}, refused);
  EXPECT_NE(refused.err.find("predicted"), std::string::npos) << refused.err;
  const json ok = boxgen_json({"analyze", "zp", "--max-seconds", "1000", "--json"});
  EXPECT_EQ(ok["pieces"],
            21);  // ZP element: 21 polynomial pieces (de Boor, Hoellig, Riemenschneider)
}

TEST(CliConventions, PredictedMemoryBeyondMaxMemoryIsRefusedNamingBoth) {
  const json e = boxgen_json({"analyze", "zp", "--estimate", "--json"});
  std::array<char, 64> predicted{};  // as the message prints it: 3 significant digits
  std::snprintf(predicted.data(), predicted.size(), "predicted %.3g MB",
                e["estimated_bytes"].get<double>() / 1e6);
  // Every command that derives shares the limit; 0.001 MB is below any prediction.
  for (const char* command : {"analyze", "eval", "pieces", "bbform"}) {
    std::vector<std::string> args{command, "zp", "--max-memory", "0.001"};
    if (std::string(command) == "eval") args.insert(args.end(), {"--at", "0 0"});
    const ProcessResult r = boxgen(args);
    EXPECT_EQ(r.exit_code, 1) << describe(args, r);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(predicted.data()), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("0.001 MB of --max-memory"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  boxgen_ok({"analyze", "zp", "--max-memory", "100000"});
}

TEST(CliConventions, MaxMemoryMustBeAFinitePositiveNumber) {
  for (const char* value : {"-5", "0", "nan", "", "inf", "lots"}) {
    const std::vector<std::string> args{"analyze", "zp", "--max-memory", value};
    const ProcessResult r = boxgen(args);
    EXPECT_EQ(r.exit_code, 2) << describe(args, r);
    EXPECT_NE(r.err.find("--max-memory"), std::string::npos) << r.err;
  }
}

TEST(CliConventions, ChecksModeIsReported) {
  const json d = boxgen_json({"analyze", "zp", "--json"});
  EXPECT_EQ(d["checks"]["mode"], "default");
  const json f = boxgen_json({"analyze", "zp", "--checks", "full", "--json"});
  EXPECT_EQ(f["checks"]["mode"], "full");
  EXPECT_EQ(f["checks"]["integral_is_one"], true);
  EXPECT_GE(f["checks"]["continuity_faces_checked"].get<int>(),
            d["checks"]["continuity_faces_checked"].get<int>());
}

TEST(CliConventions, ProgressIsSilentForShortRuns) {
  // Short derivations finish before the two-second threshold: nothing on stderr.
  const ProcessResult r = boxgen({"analyze", "zp", "--progress"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.err, "");
}

TEST(CliConventions, EvalJsonRecordsTheDerivative) {
  const json r = boxgen_json({"eval", "zp", "--at", "1/3 1/7", "--derivative", "1 0", "--json"});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0]["derivative"], json::array({1, 0}));
  const json v = boxgen_json({"eval", "zp", "--at", "1/3 1/7", "--json"});
  EXPECT_EQ(v[0]["derivative"], json::array({0, 0}));
}

// A non-symmetric spline: its prefilter on shells 0,1,2 of Z^2 (S1 = the 4 axis neighbours, S2
// = the 4 diagonal ones) weights the taps of a shell unequally. The summary may name a shell only
// if all its taps carry one weight, and must show every nonzero weight.
TEST(CliConventions, PrefilterSummaryMatchesItsTaps) {
  const std::vector<std::string> args{"prefilter", "1,0; 0,1; 1,1; 1,-1; 2,1", "--shells", "0,1,2"};
  std::vector<std::string> json_args = args;
  json_args.push_back("--json");
  const json q = boxgen_json(json_args);
  std::map<std::vector<int>, std::string> tap;
  for (const auto& w : q["weights"])
    tap[w["offset"].get<std::vector<int>>()] = w["weight"].get<std::string>();
  auto weight = [&](const std::vector<int>& p) { return tap.count(p) ? tap[p] : std::string("0"); };
  const std::vector<std::vector<std::vector<int>>> shells{{{1, 0}, {-1, 0}, {0, 1}, {0, -1}},
                                                          {{1, 1}, {-1, -1}, {1, -1}, {-1, 1}}};
  const std::string text = boxgen_ok(args);
  const size_t at = text.find("Q(z)");
  ASSERT_NE(at, std::string::npos) << text;
  const std::string line = text.substr(at, text.find('\n', at) - at);
  int non_uniform = 0;
  for (size_t s = 0; s < shells.size(); ++s) {
    bool uniform = true;
    for (const auto& p : shells[s]) uniform = uniform && weight(p) == weight(shells[s][0]);
    const std::string name = "S" + std::to_string(s + 1);
    if (!uniform) {
      ++non_uniform;
      EXPECT_EQ(line.find(name), std::string::npos) << line << ": " << name << " is not uniform";
    }
    for (const auto& p : shells[s]) {
      const std::string w = weight(p);
      if (w == "0") continue;
      EXPECT_NE(line.find(w[0] == '-' ? w.substr(1) : w), std::string::npos)
          << line << " lacks weight " << w;
    }
  }
  EXPECT_GT(non_uniform, 0) << "the example no longer has a non-uniform shell: " << line;
}

}  // namespace
}  // namespace boxgen::test
