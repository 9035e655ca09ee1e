// 8-bit images on disk: PGM (P2/P5) and PNG in, PGM and PNG out, written atomically. PNG goes
// through libpng's simplified API.
#ifndef HEX_SLAM_IO_IMAGE_IO_H_
#define HEX_SLAM_IO_IMAGE_IO_H_

#include <cstdint>
#include <string>
#include <vector>

#include "hex_slam/io/atomic_file.h"

namespace hex_slam {
namespace io {

// Row-major, top row first (as image files store it). `channels` is 1 (gray) or 3 (RGB).
struct Image {
  int width = 0;
  int height = 0;
  int channels = 1;
  std::vector<std::uint8_t> pixels;

  Image() = default;
  Image(int w, int h, int c, std::uint8_t fill = 0)
      : width(w), height(h), channels(c), pixels(static_cast<std::size_t>(w) * h * c, fill) {}
  std::uint8_t* at(int x, int y) {
    return &pixels[(static_cast<std::size_t>(y) * width + x) * channels];
  }
  const std::uint8_t* at(int x, int y) const {
    return &pixels[(static_cast<std::size_t>(y) * width + x) * channels];
  }
};

// Images larger than this many pixels are refused on read: a corrupt header must not make us
// allocate gigabytes.
constexpr std::int64_t kMaxImagePixels = std::int64_t{1} << 28;

// Reads a PGM or PNG (by content, not extension) as gray (colour averaged, as map_server does).
// Returns an empty string or an error.
std::string ReadGrayImage(const std::string& path, Image* image);

std::string WritePgm(const std::string& path, const Image& gray);
std::string WritePng(const std::string& path, const Image& image);
// The same as one file of a set written together (atomic_file.h).
void AddPgm(const std::string& path, const Image& gray, AtomicFileSet* files);
void AddPng(const std::string& path, const Image& image, AtomicFileSet* files);

}  // namespace io
}  // namespace hex_slam

#endif  // HEX_SLAM_IO_IMAGE_IO_H_
