#include "hex_slam/io/atomic_file.h"

#include <fstream>
#include <iterator>
#include <stdexcept>

#include <gtest/gtest.h>

#include "temp_dir.h"

namespace hex_slam {
namespace io {
namespace {

std::string Contents(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST(AtomicFileTest, WritesTheWholeFile) {
  testing_util::TempDir dir;
  EXPECT_EQ(WriteFileAtomically(dir.File("a.txt"), [](std::ostream& out) { out << "hello"; }), "");
  EXPECT_EQ(Contents(dir.File("a.txt")), "hello");
  EXPECT_EQ(dir.Files().size(), 1u);  // no temporary left
}

TEST(AtomicFileTest, AFailedWriteLeavesTheOldFileAndNoTemporary) {
  testing_util::TempDir dir;
  ASSERT_EQ(WriteFileAtomically(dir.File("a.txt"), [](std::ostream& out) { out << "old"; }), "");
  const std::string error = WriteFileAtomically(dir.File("a.txt"), [](std::ostream& out) {
    out << "half of the new";
    throw std::runtime_error("interrupted");
  });
  EXPECT_NE(error.find("interrupted"), std::string::npos);
  EXPECT_EQ(Contents(dir.File("a.txt")), "old");
  EXPECT_EQ(dir.Files().size(), 1u);
}

TEST(AtomicFileTest, UnwritableLocationIsAnError) {
  EXPECT_NE(WriteFileAtomically("/nonexistent_dir/x.txt", [](std::ostream& out) { out << 1; }),
            "");
}

}  // namespace
}  // namespace io
}  // namespace hex_slam
