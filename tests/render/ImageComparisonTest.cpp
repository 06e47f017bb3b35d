// The golden metric itself: it must accept a one-pixel shift and small noise, and reject a
// real change.

#include "ImageComparison.h"

#include <gtest/gtest.h>

namespace weft::test {
namespace {

render::Image withSquare(int w, int h, int x0, int y0, int size, std::uint8_t value) {
  render::Image img(w, h);
  std::fill(img.pixels.begin(), img.pixels.end(), std::uint8_t(240));
  for (int y = y0; y < y0 + size; ++y)
    for (int x = x0; x < x0 + size; ++x)
      img.at(x, y)[0] = img.at(x, y)[1] = img.at(x, y)[2] = value;
  return img;
}

TEST(ImageComparison, IdenticalImagesMatch) {
  const render::Image a = withSquare(64, 48, 10, 10, 20, 30);
  const ImageDifference d = compareImages(a, a);
  EXPECT_TRUE(d.matches({}));
  EXPECT_EQ(d.badPixels, 0u);
}

TEST(ImageComparison, OnePixelShiftIsWithinTheSearchRadius) {
  const ImageDifference d =
      compareImages(withSquare(64, 48, 10, 10, 20, 30), withSquare(64, 48, 11, 9, 20, 30));
  EXPECT_EQ(d.badPixels, 0u);
  ImageTolerance noSearch;
  noSearch.searchRadius = 0;
  EXPECT_GT(
      compareImages(withSquare(64, 48, 10, 10, 20, 30), withSquare(64, 48, 11, 9, 20, 30), noSearch)
          .badPixels,
      0u);
}

TEST(ImageComparison, SmallChannelNoiseIsBelowTheThreshold) {
  render::Image a = withSquare(64, 48, 10, 10, 20, 30), b = a;
  for (std::size_t i = 0; i < b.pixels.size(); i += 7) b.pixels[i] = std::uint8_t(b.pixels[i] - 10);
  EXPECT_TRUE(compareImages(a, b).matches({}));
}

TEST(ImageComparison, AMovedObjectFails) {
  const ImageDifference d =
      compareImages(withSquare(64, 48, 10, 10, 20, 30), withSquare(64, 48, 30, 20, 20, 30));
  EXPECT_FALSE(d.matches({}));
  EXPECT_EQ(d.diff.width, 64);
  EXPECT_EQ(d.diff.at(12, 12)[0], 255);  // marked red in the diff
  EXPECT_EQ(d.diff.at(12, 12)[1], 0);
}

TEST(ImageComparison, AMissingThinLineFailsBothWays) {
  // A one-pixel line through a blank image: every line pixel finds blank neighbours, so only
  // the reverse check (from the image that has the line) sees it.
  render::Image blank(64, 48), line(64, 48);
  std::fill(blank.pixels.begin(), blank.pixels.end(), std::uint8_t(240));
  line = blank;
  for (int x = 0; x < 64; ++x) line.at(x, 20)[0] = line.at(x, 20)[1] = line.at(x, 20)[2] = 0;
  ImageTolerance strict;
  strict.maxBadShare = 0.0;
  EXPECT_FALSE(compareImages(blank, line, strict).matches(strict));
  EXPECT_FALSE(compareImages(line, blank, strict).matches(strict));
}

TEST(ImageComparison, DifferentSizesNeverMatch) {
  EXPECT_FALSE(compareImages(render::Image(10, 10), render::Image(10, 11)).matches({}));
}

}  // namespace
}  // namespace weft::test
