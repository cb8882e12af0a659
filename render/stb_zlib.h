// The zlib level stb_image_write's deflate hook (stb_impl.cpp) compresses with, set per thread by
// encodePng() so that encoder threads with different options do not race.
#pragma once

namespace render::detail {

extern thread_local int pngZlibLevel;

}  // namespace render::detail
