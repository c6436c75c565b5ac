// Points files (runtime/points_file.h): what users' files hold besides points, and the errors.
#include "runtime/points_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace boxgen::runtime {
namespace {

std::string error_of(std::string_view text) {
  try {
    (void)parse_points(text, "pts.txt");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for '" << text << "'";
  return "";
}

TEST(PointsFile, BlankLinesCommentsCrlfAndBomAreAccepted) {
  const std::vector<Vec3> expected = {{0, 0, 0}, {0.5, -0.25, 0.125}, {-1, 1e-3, 2}};
  EXPECT_EQ(parse_points("0 0 0\n0.5 -0.25 0.125\n-1 1e-3 2\n", "p"), expected);
  EXPECT_EQ(parse_points("0 0 0\n0.5 -0.25 0.125\n-1 1e-3 2", "p"), expected);  // no final newline
  EXPECT_EQ(parse_points("\n\n0 0 0\n \t \n0.5 -0.25 0.125\n\n-1 1e-3 2\n\n", "p"), expected);
  EXPECT_EQ(parse_points("# x y z\n0 0 0 # origin\n#1 1 1\n0.5 -0.25 0.125#\n-1 1e-3 2\n", "p"),
            expected);
  EXPECT_EQ(parse_points("0 0 0\r\n0.5 -0.25 0.125\r\n-1 1e-3 2\r\n", "p"), expected);
  EXPECT_EQ(parse_points("\xEF\xBB\xBF"
                         "0 0 0\n0.5 -0.25 0.125\n-1 1e-3 2\n",
                         "p"),
            expected);
  EXPECT_EQ(parse_points("+0 0 -0\n0.5\t-0.25\t+0.125\n-0x1p0 0.001 2.\n", "p"), expected);
  EXPECT_TRUE(parse_points("", "p").empty());
  EXPECT_TRUE(parse_points("# nothing\n\r\n", "p").empty());
}

TEST(PointsFile, BadLinesNameTheFileAndLine) {
  EXPECT_EQ(error_of("0 0 0\n0 x 0\n"),
            "pts.txt:2: expected three numbers 'x y z', 'x' is not a number");
  EXPECT_EQ(error_of("# c\n\n0 0\n"), "pts.txt:3: expected three numbers 'x y z', found 2");
  EXPECT_EQ(error_of("0 0 0 0\n"), "pts.txt:1: expected three numbers 'x y z', found more ('0')");
  EXPECT_EQ(error_of("0 nan 0\n"), "pts.txt:1: the coordinate 'nan' is not finite");
  EXPECT_EQ(error_of("0 0 -inf\n"), "pts.txt:1: the coordinate '-inf' is not finite");
  EXPECT_EQ(error_of("0 0 1e999\n"),
            "pts.txt:1: expected three numbers 'x y z', '1e999' is not a number");
  EXPECT_EQ(error_of("0 0 ++1\n"),
            "pts.txt:1: expected three numbers 'x y z', '++1' is not a number");
  EXPECT_EQ(error_of("0 0 1,\n"),
            "pts.txt:1: expected three numbers 'x y z', '1,' is not a number");
  EXPECT_NE(error_of(std::string("0 0 0\n1 2\0 3\n", 12)).find("pts.txt:2: "), std::string::npos);
  // A BOM is only a BOM at the start.
  EXPECT_NE(error_of("0 0 0\n\xEF\xBB\xBF"
                     "1 1 1\n")
                .find("pts.txt:2:"),
            std::string::npos);
}

TEST(PointsFile, DirectoriesAndMissingFilesAreErrors) {
  EXPECT_THROW((void)read_points_file("/"), std::invalid_argument);
  EXPECT_THROW((void)read_points_file("/nonexistent/points.txt"), std::invalid_argument);
  try {
    (void)read_points_file("/tmp");
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("directory"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace boxgen::runtime
