#include "hex_slam/io/image_io.h"

#include <png.h>

#include <cctype>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>

#include "hex_slam/io/atomic_file.h"

namespace hex_slam {
namespace io {
namespace {

constexpr unsigned char kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

bool ReadAll(const std::string& path, std::string* bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  bytes->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return true;
}

// PGM header tokens, skipping whitespace and '#' comments.
bool NextToken(const std::string& bytes, std::size_t* pos, std::string* token) {
  token->clear();
  while (*pos < bytes.size()) {
    const char c = bytes[*pos];
    if (c == '#') {
      while (*pos < bytes.size() && bytes[*pos] != '\n') ++*pos;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      ++*pos;
    } else {
      break;
    }
  }
  while (*pos < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[*pos]))) {
    *token += bytes[(*pos)++];
  }
  return !token->empty();
}

bool ParseInt(const std::string& token, long long limit, int* out) {
  if (token.empty() || token.size() > 10) return false;
  for (char c : token) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  }
  const long long value = std::stoll(token);
  if (value <= 0 || value > limit) return false;
  *out = static_cast<int>(value);
  return true;
}

std::string ReadPgm(const std::string& path, const std::string& bytes, Image* image) {
  std::size_t pos = 0;
  std::string magic, w, h, maxval;
  if (!NextToken(bytes, &pos, &magic) || (magic != "P5" && magic != "P2")) {
    return path + ": not a PGM file";
  }
  int width = 0, height = 0, max_value = 0;
  if (!NextToken(bytes, &pos, &w) || !NextToken(bytes, &pos, &h) ||
      !NextToken(bytes, &pos, &maxval) || !ParseInt(w, 1 << 20, &width) ||
      !ParseInt(h, 1 << 20, &height) || !ParseInt(maxval, 65535, &max_value)) {
    return path + ": corrupt PGM header";
  }
  if (static_cast<std::int64_t>(width) * height > kMaxImagePixels) {
    return path + ": image too large";
  }
  *image = Image(width, height, 1);
  const std::size_t n = image->pixels.size();
  if (magic == "P5") {
    ++pos;  // the single whitespace after maxval
    const std::size_t sample_bytes = max_value > 255 ? 2 : 1;
    if (bytes.size() < pos + n * sample_bytes) return path + ": truncated PGM data";
    for (std::size_t i = 0; i < n; ++i) {
      unsigned value = static_cast<unsigned char>(bytes[pos + i * sample_bytes]);
      if (sample_bytes == 2) {
        value = (value << 8) | static_cast<unsigned char>(bytes[pos + 2 * i + 1]);
      }
      image->pixels[i] = static_cast<std::uint8_t>(value * 255 / max_value);
    }
  } else {
    std::string token;
    for (std::size_t i = 0; i < n; ++i) {
      int value = 0;
      if (!NextToken(bytes, &pos, &token)) return path + ": truncated PGM data";
      if (token != "0" && !ParseInt(token, max_value, &value)) return path + ": bad PGM sample";
      image->pixels[i] = static_cast<std::uint8_t>(value * 255 / max_value);
    }
  }
  return "";
}

std::string ReadPng(const std::string& path, const std::string& bytes, Image* image) {
  png_image png;
  std::memset(&png, 0, sizeof(png));
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&png, bytes.data(), bytes.size())) {
    return path + ": corrupt PNG (" + png.message + ")";
  }
  if (static_cast<std::int64_t>(png.width) * png.height > kMaxImagePixels) {
    png_image_free(&png);
    return path + ": image too large";
  }
  png.format = PNG_FORMAT_GRAY;  // libpng converts colour to gray and composites alpha on black
  *image = Image(static_cast<int>(png.width), static_cast<int>(png.height), 1);
  if (!png_image_finish_read(&png, nullptr, image->pixels.data(), 0, nullptr)) {
    const std::string message = png.message;
    png_image_free(&png);
    return path + ": corrupt PNG data (" + message + ")";
  }
  return "";
}

}  // namespace

std::string ReadGrayImage(const std::string& path, Image* image) {
  std::string bytes;
  if (!ReadAll(path, &bytes)) return "cannot read " + path;
  if (bytes.size() >= sizeof(kPngSignature) &&
      std::memcmp(bytes.data(), kPngSignature, sizeof(kPngSignature)) == 0) {
    return ReadPng(path, bytes, image);
  }
  return ReadPgm(path, bytes, image);
}

void AddPgm(const std::string& path, const Image& gray, AtomicFileSet* files) {
  if (gray.channels != 1) return files->Fail("WritePgm: image must be gray");
  files->Add(path, [&gray](std::ostream& out) {
    out << "P5\n# hex_slam\n" << gray.width << " " << gray.height << "\n255\n";
    out.write(reinterpret_cast<const char*>(gray.pixels.data()),
              static_cast<std::streamsize>(gray.pixels.size()));
  });
}

std::string WritePgm(const std::string& path, const Image& gray) {
  AtomicFileSet file;
  AddPgm(path, gray, &file);
  return file.Commit();
}

std::string WritePng(const std::string& path, const Image& image) {
  AtomicFileSet file;
  AddPng(path, image, &file);
  return file.Commit();
}

void AddPng(const std::string& path, const Image& image, AtomicFileSet* files) {
  if (image.channels != 1 && image.channels != 3) return files->Fail("WritePng: 1 or 3 channels");
  png_image png;
  std::memset(&png, 0, sizeof(png));
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = image.channels == 1 ? PNG_FORMAT_GRAY : PNG_FORMAT_RGB;
  // Fast deflate: maps and plots are big, flat images, and the default level spent most of
  // hex_slam_offline's wall time (Intel: 1.9 of 2.2 s) for files a third smaller. One encoding
  // into a buffer of the largest size it can take, not one to measure and one to write. The
  // buffer is left uninitialised: that size is the image's raw bytes and more (Intel's map: 54
  // MB for a 1.7 MB file), and zeroing it made every page resident, the offline tool's peak.
  png.flags = PNG_IMAGE_FLAG_FAST;
  png_alloc_size_t size = PNG_IMAGE_PNG_SIZE_MAX(png);
  std::unique_ptr<char[]> buffer(new char[size]);
  if (!png_image_write_to_memory(&png, buffer.get(), &size, 0, image.pixels.data(), 0, nullptr)) {
    return files->Fail(std::string("PNG encoding failed: ") + png.message);
  }
  files->Add(path, [&buffer, size](std::ostream& out) {
    out.write(buffer.get(), static_cast<std::streamsize>(size));
  });
}

}  // namespace io
}  // namespace hex_slam
