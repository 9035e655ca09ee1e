#include "hex_slam/io/image_io.h"

#include <fstream>

#include <gtest/gtest.h>

#include "temp_dir.h"

namespace hex_slam {
namespace io {
namespace {

Image Gradient(int w, int h) {
  Image image(w, h, 1);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) *image.at(x, y) = static_cast<std::uint8_t>((x * 7 + y * 13) % 256);
  }
  return image;
}

void WriteRaw(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

TEST(ImageIoTest, PgmRoundTrip) {
  testing_util::TempDir dir;
  const Image image = Gradient(37, 11);
  ASSERT_EQ(WritePgm(dir.File("g.pgm"), image), "");
  Image back;
  ASSERT_EQ(ReadGrayImage(dir.File("g.pgm"), &back), "");
  EXPECT_EQ(back.width, 37);
  EXPECT_EQ(back.height, 11);
  EXPECT_EQ(back.pixels, image.pixels);
}

TEST(ImageIoTest, PngRoundTripGrayAndColourReadsAsGray) {
  testing_util::TempDir dir;
  const Image gray = Gradient(20, 9);
  ASSERT_EQ(WritePng(dir.File("g.png"), gray), "");
  Image back;
  ASSERT_EQ(ReadGrayImage(dir.File("g.png"), &back), "");
  EXPECT_EQ(back.pixels, gray.pixels);

  Image rgb(2, 1, 3);
  rgb.pixels = {255, 255, 255, 0, 0, 0};
  ASSERT_EQ(WritePng(dir.File("c.png"), rgb), "");
  ASSERT_EQ(ReadGrayImage(dir.File("c.png"), &back), "");
  ASSERT_EQ(back.channels, 1);
  EXPECT_EQ(back.pixels[0], 255);
  EXPECT_EQ(back.pixels[1], 0);
}

TEST(ImageIoTest, AsciiPgmWithCommentsAndSixteenBitMaxval) {
  testing_util::TempDir dir;
  WriteRaw(dir.File("a.pgm"), "P2\n# a comment\n3 1\n# another\n1000\n0 500 1000\n");
  Image image;
  ASSERT_EQ(ReadGrayImage(dir.File("a.pgm"), &image), "");
  EXPECT_EQ(image.pixels, (std::vector<std::uint8_t>{0, 127, 255}));
}

TEST(ImageIoTest, CorruptAndTruncatedFilesAreErrors) {
  testing_util::TempDir dir;
  Image image;
  EXPECT_NE(ReadGrayImage(dir.File("missing.pgm"), &image), "");
  WriteRaw(dir.File("text.pgm"), "hello world");
  EXPECT_NE(ReadGrayImage(dir.File("text.pgm"), &image), "");
  WriteRaw(dir.File("short.pgm"), "P5\n10 10\n255\n" + std::string(50, 'x'));
  EXPECT_NE(ReadGrayImage(dir.File("short.pgm"), &image).find("truncated"), std::string::npos);
  WriteRaw(dir.File("huge.pgm"), "P5\n1000000 1000000\n255\n");
  EXPECT_NE(ReadGrayImage(dir.File("huge.pgm"), &image).find("too large"), std::string::npos);
  WriteRaw(dir.File("neg.pgm"), "P5\n-3 2\n255\n");
  EXPECT_NE(ReadGrayImage(dir.File("neg.pgm"), &image), "");
  // A PNG cut in half.
  ASSERT_EQ(WritePng(dir.File("ok.png"), Gradient(64, 64)), "");
  std::ifstream in(dir.File("ok.png"), std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  WriteRaw(dir.File("cut.png"), bytes.substr(0, bytes.size() / 2));
  EXPECT_NE(ReadGrayImage(dir.File("cut.png"), &image), "");
}

}  // namespace
}  // namespace io
}  // namespace hex_slam
