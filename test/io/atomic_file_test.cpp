#include "hex_slam/io/atomic_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <iterator>
#include <stdexcept>
#include <vector>

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

TEST(AtomicFileSetTest, AllFilesAppearTogetherOrNoneDoes) {
  testing_util::TempDir dir;
  {
    AtomicFileSet files;
    files.Add(dir.File("a.txt"), [](std::ostream& out) { out << "A"; });
    files.Add(dir.File("b.txt"), [](std::ostream& out) { out << "B"; });
    EXPECT_TRUE(Contents(dir.File("a.txt")).empty()) << "renamed before the set was complete";
    ASSERT_EQ(files.Commit(), "");
  }
  EXPECT_EQ(Contents(dir.File("a.txt")), "A");
  EXPECT_EQ(Contents(dir.File("b.txt")), "B");
  EXPECT_EQ(dir.Files().size(), 2u);
  // The second file fails: the first keeps its old contents, and no temporary stays.
  AtomicFileSet failing;
  failing.Add(dir.File("a.txt"), [](std::ostream& out) { out << "new A"; });
  failing.Add(dir.File("b.txt"), [](std::ostream&) { throw std::runtime_error("no B"); });
  failing.Add(dir.File("c.txt"), [](std::ostream& out) { out << "C"; });
  EXPECT_NE(failing.Commit().find("no B"), std::string::npos);
  EXPECT_EQ(Contents(dir.File("a.txt")), "A");
  EXPECT_EQ(dir.Files().size(), 2u);
}

TEST(AtomicFileSetTest, ATargetThatIsADirectoryFailsTheSetBeforeAnyRename) {
  // Issue 12: save_map whose .yaml target was a directory left a stray .pgm behind.
  testing_util::TempDir dir;
  ASSERT_EQ(::mkdir(dir.File("m.yaml").c_str(), 0755), 0);
  AtomicFileSet files;
  files.Add(dir.File("m.pgm"), [](std::ostream& out) { out << "P5"; });
  files.Add(dir.File("m.yaml"), [](std::ostream& out) { out << "image: m.pgm"; });
  EXPECT_EQ(files.Commit(), "cannot write " + dir.File("m.yaml") + ": a directory");
  EXPECT_EQ(dir.Files(), std::vector<std::string>{"m.yaml"});
  ::rmdir(dir.File("m.yaml").c_str());
}

TEST(AtomicFileSetTest, AnUncommittedSetLeavesNothing) {
  testing_util::TempDir dir;
  {
    AtomicFileSet files;
    files.Add(dir.File("a.txt"), [](std::ostream& out) { out << "A"; });
    files.Fail("the data was bad");
    files.Add(dir.File("b.txt"), [](std::ostream& out) { out << "B"; });  // ignored after Fail
  }
  EXPECT_TRUE(dir.Files().empty());
  AtomicFileSet failed;
  failed.Fail("the data was bad");
  EXPECT_EQ(failed.Commit(), "the data was bad");
}

TEST(AtomicFileTest, UnwritableLocationIsAnError) {
  EXPECT_NE(WriteFileAtomically("/nonexistent_dir/x.txt", [](std::ostream& out) { out << 1; }),
            "");
}

}  // namespace
}  // namespace io
}  // namespace hex_slam
