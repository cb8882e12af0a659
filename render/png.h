// PNG files: encoding with stb_image_write (its deflate replaced by zlib's), atomic writes,
// reading with stb_image.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "render/image.h"

namespace render {

struct PngOptions {
  // zlib level 1-9. On rendered frames level 1 comes within 10% of level 6's size in 60% of
  // its time (figures in render/README.md).
  int level = 1;
};

// The PNG file's bytes (RGBA, 8 bits per channel). Throws std::runtime_error on failure.
std::vector<std::uint8_t> encodePng(const Image& image, const PngOptions& options = {});

// Writes `bytes` to `path` through a temporary file in the same directory and a rename, so a
// killed run never leaves a half-written file under the final name. Throws std::runtime_error
// "render: cannot write '<path>': <reason>" (an unwritable or missing directory, a full disk).
void writeFileAtomically(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes);

void writePng(const std::filesystem::path& path, const Image& image,
              const PngOptions& options = {});

// Reads a PNG as RGBA8 (grey and RGB are expanded); throws std::runtime_error naming the path:
// "render: cannot read PNG '<path>': <the system's reason>" when it cannot be opened, "...: not a
// valid PNG file (stb_image: <reason>)" when it cannot be decoded.
Image readPng(const std::filesystem::path& path);

// "frame_000123.png": six digits, more when the index needs them.
std::string frameFileName(std::int64_t index, const std::string& prefix = "frame_");

}  // namespace render
