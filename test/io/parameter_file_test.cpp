#include "hex_slam/io/parameter_file.h"

#include <fstream>

#include <gtest/gtest.h>

#include "hex_slam/mapping/slam_options.h"
#include "temp_dir.h"

namespace hex_slam {
namespace io {
namespace {

TEST(ParameterFileTest, ReadsScalarsThatTheTableApplies) {
  testing_util::TempDir dir;
  std::ofstream(dir.File("p.yaml")) << "# a robot\nmap_resolution: 0.05\nlattice: square\n"
                                       "map_auto_grow: false\nmap_size: 512\n";
  std::map<std::string, std::string> values;
  ASSERT_EQ(ReadParameterFile(dir.File("p.yaml"), &values), "");
  SlamOptions options;
  ParameterTable table = SlamParameterTable(&options);
  EXPECT_TRUE(table.Apply(values).empty());
  EXPECT_DOUBLE_EQ(options.map_resolution, 0.05);
  EXPECT_EQ(options.lattice, "square");
  EXPECT_FALSE(options.map_auto_grow);
  EXPECT_EQ(options.map_size, 512);
}

TEST(ParameterFileTest, BadFilesAreErrors) {
  testing_util::TempDir dir;
  std::map<std::string, std::string> values;
  EXPECT_NE(ReadParameterFile(dir.File("missing.yaml"), &values), "");
  std::ofstream(dir.File("list.yaml")) << "- a\n- b\n";
  EXPECT_NE(ReadParameterFile(dir.File("list.yaml"), &values), "");
  std::ofstream(dir.File("nested.yaml")) << "matcher:\n  iterations: 3\n";
  EXPECT_NE(ReadParameterFile(dir.File("nested.yaml"), &values).find("matcher"),
            std::string::npos);
  std::ofstream(dir.File("broken.yaml")) << "a: [1, 2\n";
  EXPECT_NE(ReadParameterFile(dir.File("broken.yaml"), &values), "");
  std::ofstream(dir.File("empty.yaml")) << "";
  EXPECT_EQ(ReadParameterFile(dir.File("empty.yaml"), &values), "");
  // A key that is itself a mapping or a list threw yaml-cpp's conversion error out of the reader.
  EXPECT_NE(ParseParameterText("{a: 1}: 2\n", "p.yaml", &values).find("name is not a single"),
            std::string::npos);
  EXPECT_NE(ParseParameterText("[a]: 2\n", "p.yaml", &values), "");
}

TEST(ParameterFileTest, AFileWithoutEndIsRefusedAtOneMebibyte) {
  std::map<std::string, std::string> values;
  EXPECT_EQ(ReadParameterFile("/dev/zero", &values),
            "/dev/zero: larger than 1048576 bytes, not a parameter file");
}

}  // namespace
}  // namespace io
}  // namespace hex_slam
