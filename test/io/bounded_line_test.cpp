#include "hex_slam/io/bounded_line.h"

#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

namespace hex_slam {
namespace io {
namespace {

std::vector<std::string> Lines(const std::string& text, std::size_t cap, LineStatus* last) {
  std::istringstream in(text);
  std::vector<std::string> lines;
  std::string line;
  while ((*last = ReadBoundedLine(in, cap, &line)) == LineStatus::kLine) lines.push_back(line);
  return lines;
}

TEST(BoundedLineTest, SplitsAsGetlineDoes) {
  // Against std::getline itself, the reader's model, on the cases that differ most often:
  // a last line without '\n', empty lines, '\r' kept.
  for (const std::string text : {"", "\n", "a", "a\n", "a\nb", "a\n\nb\n\n", "x\r\ny\r\n"}) {
    std::istringstream reference(text);
    std::vector<std::string> expected;
    for (std::string l; std::getline(reference, l);) expected.push_back(l);
    LineStatus last = LineStatus::kLine;
    EXPECT_EQ(Lines(text, 100, &last), expected) << "'" << text << "'";
    EXPECT_EQ(last, LineStatus::kEnd);
  }
}

TEST(BoundedLineTest, ALineLongerThanTheCapIsRefusedAtTheCap) {
  LineStatus last = LineStatus::kLine;
  EXPECT_EQ(Lines("12345\n123456\n", 5, &last), std::vector<std::string>{"12345"});
  EXPECT_EQ(last, LineStatus::kTooLong);
  EXPECT_EQ(LineTooLongMessage("f.clf", 2, 5), "f.clf:2: line is longer than 5 bytes (not a "
                                               "text file?)");
}

TEST(BoundedLineTest, DevZeroEndsAtTheCapInsteadOfGrowingWithoutBound) {
  std::ifstream in("/dev/zero");
  ASSERT_TRUE(in.good());
  std::string line;
  EXPECT_EQ(ReadBoundedLine(in, 1 << 20, &line), LineStatus::kTooLong);
  EXPECT_EQ(line.size(), std::size_t{1} << 20);
}

}  // namespace
}  // namespace io
}  // namespace hex_slam
