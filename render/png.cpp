#include "render/png.h"

#include <stb_image.h>
#include <stb_image_write.h>
#include <unistd.h>

#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <system_error>

#include "render/stb_zlib.h"

namespace render {

namespace detail {
thread_local int pngZlibLevel = 1;
}  // namespace detail

namespace {

// stb's default tries all five PNG row filters on every row and keeps its best guess, which
// costs more than the deflate. Measured on 640x360 frames (render/README.md): no filter (0) is
// the fastest and also the smallest with zlib level 1, on a busy frame of 2,000 small shapes
// (8.8 ms, 233 KB against 15.1 ms, 280 KB for the default) and on a flat one (2.4 ms, 26 KB);
// "up" (2) and Paeth (4) lose on both. stb reads this from a global, so it is set once for the
// process, before any encoder runs.
constexpr int kPngFilter = 0;

void configureStbOnce() {
  static std::once_flag once;
  std::call_once(once, [] { stbi_write_force_png_filter = kPngFilter; });
}

void appendBytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(context);
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  out->insert(out->end(), bytes, bytes + size);
}

}  // namespace

std::vector<std::uint8_t> encodePng(const Image& image, const PngOptions& options) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != static_cast<std::size_t>(image.width) * image.height * 4) {
    throw std::runtime_error("render: cannot encode a PNG of an empty or inconsistent image (" +
                             std::to_string(image.width) + "x" + std::to_string(image.height) +
                             ", " + std::to_string(image.rgba.size()) + " bytes)");
  }
  if (options.level < 1 || options.level > 9) {
    throw std::invalid_argument("render: PNG zlib level must be 1 to 9, got " +
                                std::to_string(options.level));
  }
  configureStbOnce();
  detail::pngZlibLevel = options.level;
  std::vector<std::uint8_t> out;
  out.reserve(image.rgba.size() / 8);
  if (!stbi_write_png_to_func(&appendBytes, &out, image.width, image.height, 4, image.rgba.data(),
                              static_cast<int>(image.stride()))) {
    throw std::runtime_error("render: PNG encoding failed (out of memory?)");
  }
  return out;
}

void writeFileAtomically(const std::filesystem::path& path,
                         const std::vector<std::uint8_t>& bytes) {
  // The temporary name keeps the final extension off, so "*.png" never matches a partial file.
  std::filesystem::path temporary = path;
  temporary += ".tmp" + std::to_string(::getpid());
  auto fail = [&](int error) {
    std::remove(temporary.c_str());
    throw std::runtime_error("render: cannot write '" + path.string() +
                             "': " + std::strerror(error));
  };
  std::FILE* f = std::fopen(temporary.c_str(), "wb");
  if (f == nullptr) fail(errno);
  bool ok = bytes.empty() || std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
  int error = errno;
  if (std::fclose(f) != 0 && ok) {
    ok = false;
    error = errno;
  }
  if (!ok) fail(error);
  if (std::rename(temporary.c_str(), path.c_str()) != 0) fail(errno);
}

void writePng(const std::filesystem::path& path, const Image& image, const PngOptions& options) {
  writeFileAtomically(path, encodePng(image, options));
}

Image readPng(const std::filesystem::path& path) {
  // Opened here rather than by stb, whose only message for a missing file is "can't fopen".
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) {
    throw std::runtime_error("render: cannot read PNG '" + path.string() +
                             "': " + std::strerror(errno));
  }
  int w = 0, h = 0, channels = 0;
  stbi_uc* pixels = stbi_load_from_file(f, &w, &h, &channels, 4);
  std::fclose(f);
  if (pixels == nullptr) {
    throw std::runtime_error("render: cannot read PNG '" + path.string() +
                             "': not a valid PNG file (stb_image: " + stbi_failure_reason() + ")");
  }
  Image image(w, h);
  std::memcpy(image.rgba.data(), pixels, image.rgba.size());
  stbi_image_free(pixels);
  return image;
}

std::string frameFileName(std::int64_t index, const std::string& prefix) {
  char digits[32];
  std::snprintf(digits, sizeof digits, "%06" PRId64, index);
  return prefix + digits + ".png";
}

}  // namespace render
