// Contact sheet: thumbnails in a grid, shrunk by area averaging.
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "render/contact_sheet.h"
#include "render_support.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace contact_sheet_test {

using render::Color;
using render::Image;

Image solid(int w, int h, Color c) {
  Image image(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x)
      image.setPixel(x, y, c);
  }
  return image;
}

TEST(ContactSheet, LaysThumbnailsOutLeftToRightThenDown) {
  const Color colours[] = {render::colors::kRed, render::colors::kGreen, render::colors::kBlue,
                           render::colors::kYellow, render::colors::kWhite};
  std::vector<Image> frames;
  for (Color c : colours)
    frames.push_back(solid(64, 36, c));
  render::ContactSheetOptions options;
  options.columns = 2;
  options.thumbWidth = 16;
  options.gap = 2;
  Image sheet = render::contactSheet(frames, options);
  // Thumbnails are 16x9; three rows of two.
  EXPECT_EQ(sheet.width, 2 + 2 * 18);
  EXPECT_EQ(sheet.height, 2 + 3 * 11);
  EXPECT_PIXEL(sheet, 2 + 8, 2 + 4, render::colors::kRed, 0);
  EXPECT_PIXEL(sheet, 20 + 8, 2 + 4, render::colors::kGreen, 0);
  EXPECT_PIXEL(sheet, 2 + 8, 13 + 4, render::colors::kBlue, 0);
  EXPECT_PIXEL(sheet, 20 + 8, 13 + 4, render::colors::kYellow, 0);
  EXPECT_PIXEL(sheet, 2 + 8, 24 + 4, render::colors::kWhite, 0);
  EXPECT_PIXEL(sheet, 20 + 8, 24 + 4, render::colors::kBlack, 0);  // no sixth frame
  EXPECT_PIXEL(sheet, 1, 1, render::colors::kBlack, 0);            // the gap
}

TEST(ContactSheet, ShrinkingAveragesInsteadOfSkipping) {
  // One-pixel black and white stripes shrink to grey, not to one of the two.
  Image stripes(64, 64);
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      stripes.setPixel(x, y, x % 2 ? render::colors::kWhite : render::colors::kBlack);
    }
  }
  Image small = render::resizeArea(stripes, 10, 10);
  for (int x = 0; x < 10; ++x)
    EXPECT_NEAR(small.pixel(x, 5).r, 128, 14) << x;
  EXPECT_THROW(render::contactSheet(std::vector<Image>{}), std::invalid_argument);
}

}  // namespace contact_sheet_test
