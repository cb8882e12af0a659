// A contact sheet: many frames shrunk into a grid in one image, for a look at a whole run.
#pragma once

#include <span>

#include "render/color.h"
#include "render/image.h"

namespace render {

struct ContactSheetOptions {
  int columns = 6;
  int thumbWidth = 160;  // pixels; the height keeps the first frame's aspect ratio
  int gap = 2;           // pixels between and around thumbnails
  Color background = colors::kBlack;
};

// Thumbnails of `frames` left to right, top to bottom, each an area average of its frame (no
// aliasing however much it shrinks). Frames of another size than the first are scaled to the
// same thumbnail size. Throws std::invalid_argument for no frames or bad options.
Image contactSheet(std::span<const Image> frames, const ContactSheetOptions& options = {});

// `image` scaled to width x height by averaging the source pixels each target pixel covers.
Image resizeArea(const Image& image, int width, int height);

}  // namespace render
