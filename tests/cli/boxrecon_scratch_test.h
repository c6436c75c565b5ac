// A test fixture for boxrecon runs that write files: a scratch directory of its own, file paths
// in it, and ok() for a command that must succeed.
#pragma once
#include <string>
#include <vector>

#include "cli_support.h"
#include "tests/support/scratch_directory.h"

namespace boxgen::test {

class BoxreconScratchTest : public ScratchDirectoryTest {
 protected:
  explicit BoxreconScratchTest(const std::string& name) : ScratchDirectoryTest(name) {}
  std::string file(const std::string& name) const { return (dir_ / name).string(); }

  // Exit 0 and nothing on stderr; returns stdout.
  std::string ok(const std::vector<std::string>& args) {
    const ProcessResult r = boxrecon(args);
    EXPECT_TRUE(r.exited && r.exit_code == 0) << describe(args, r);
    EXPECT_EQ(r.err, "") << describe(args, r);
    return r.out;
  }
};

}  // namespace boxgen::test
