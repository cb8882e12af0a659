// The stb implementations, compiled once here with warnings off for this file alone (third-party
// code; see render/CMakeLists.txt). Debian's libstb.a is not used: we need our own
// STBIW_ZLIB_COMPRESS, and only the PNG decoder.
#include <zlib.h>

#include <cstdlib>

#include "render/stb_zlib.h"

namespace {

// stb_image_write's own deflate ignores levels below 5 and takes 2.5x as long as zlib's
// level 1 on our frames (render/README.md). Returns malloc'd memory, which stb frees.
unsigned char* zlibCompress(unsigned char* data, int length, int* outLength, int /*quality*/) {
  uLongf size = compressBound(static_cast<uLong>(length));
  auto* out = static_cast<unsigned char*>(std::malloc(size));
  if (out == nullptr) return nullptr;
  if (compress2(out, &size, data, static_cast<uLong>(length), render::detail::pngZlibLevel) !=
      Z_OK) {
    std::free(out);
    return nullptr;
  }
  *outLength = static_cast<int>(size);
  return out;
}

}  // namespace

#define STBIW_ZLIB_COMPRESS zlibCompress
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

#define STBI_ONLY_PNG
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

#define STB_TRUETYPE_IMPLEMENTATION
#include <stb_truetype.h>
