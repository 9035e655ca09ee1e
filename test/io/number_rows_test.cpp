#include "hex_slam/io/number_rows.h"

#include <fstream>
#include <vector>

#include <gtest/gtest.h>

#include "temp_dir.h"

namespace hex_slam {
namespace io {
namespace {

std::vector<std::vector<double>> Read(const std::string& path, int columns, std::string* error) {
  std::vector<std::vector<double>> rows;
  *error = ReadNumberRows(path, columns, "a b c", [&rows, columns](const double* v) {
    rows.emplace_back(v, v + columns);
    return v[0] < 0.0 ? "a is negative" : "";
  });
  return rows;
}

TEST(NumberRowsTest, ReadsRecordsSkippingCommentsBlanksAndExtraFields) {
  testing_util::TempDir dir;
  std::ofstream(dir.File("ok.txt")) << "# a b c\n\n  1 2 3\n\t# indented comment\n4 -5e-1 6 extra\r\n";
  std::string error;
  const auto rows = Read(dir.File("ok.txt"), 3, &error);
  EXPECT_EQ(error, "");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1], (std::vector<double>{4, -0.5, 6}));
}

TEST(NumberRowsTest, ShortNonNumericAndNonFiniteRecordsNameTheirLine) {
  testing_util::TempDir dir;
  std::string error;
  for (const char* bad : {"1 2\n", "1 x 3\n", "1 nan 3\n", "1 2 inf\n"}) {
    std::ofstream(dir.File("bad.txt")) << "1 2 3\n" << bad;
    Read(dir.File("bad.txt"), 3, &error);
    EXPECT_NE(error.find("bad.txt:2: expected 3 finite numbers (a b c)"), std::string::npos)
        << bad << " -> " << error;
  }
  Read(dir.File("missing.txt"), 3, &error);
  EXPECT_NE(error.find("cannot read"), std::string::npos);
}

TEST(NumberRowsTest, TheRowsVerdictNamesTheLine) {
  testing_util::TempDir dir;
  std::ofstream(dir.File("neg.txt")) << "1 2 3\n-1 2 3\n";
  std::string error;
  Read(dir.File("neg.txt"), 3, &error);
  EXPECT_EQ(error, dir.File("neg.txt") + ":2: a is negative");
}

TEST(NumberRowsTest, ALineLongerThan64KiBOrDevZeroIsAnErrorNotUnboundedMemory) {
  // Issue 12: hex_slam_eval on /dev/zero grew without bound.
  std::string error;
  Read("/dev/zero", 3, &error);
  EXPECT_NE(error.find("/dev/zero:1: line is longer than 65536 bytes"), std::string::npos) << error;
  testing_util::TempDir dir;
  std::ofstream(dir.File("long.txt")) << "1 2 3\n" << std::string(70000, ' ') << "4 5 6\n";
  Read(dir.File("long.txt"), 3, &error);
  EXPECT_NE(error.find("long.txt:2: line is longer"), std::string::npos) << error;
}

}  // namespace
}  // namespace io
}  // namespace hex_slam
