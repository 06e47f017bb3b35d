#include "ImageComparison.h"

#include <algorithm>
#include <cstdlib>

namespace weft::test {
namespace {

// True when a pixel within `radius` of (x, y) in `other` is within `threshold` of `p`.
bool hasNearMatch(const std::uint8_t* p, const render::Image& other, int x, int y, int radius,
                  int threshold) {
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx) {
      const int ox = x + dx, oy = y + dy;
      if (ox < 0 || oy < 0 || ox >= other.width || oy >= other.height) continue;
      const std::uint8_t* q = other.at(ox, oy);
      if (std::abs(p[0] - q[0]) <= threshold && std::abs(p[1] - q[1]) <= threshold &&
          std::abs(p[2] - q[2]) <= threshold)
        return true;
    }
  return false;
}

}  // namespace

std::string ImageDifference::describe(const ImageTolerance& t) const {
  if (!sameSize) return "images differ in size";
  return std::to_string(badPixels) + " pixels (" + std::to_string(100.0 * badShare) +
         " %) differ by more than " + std::to_string(t.channelThreshold) + " per channel within " +
         std::to_string(t.searchRadius) + " pixel(s); allowed " +
         std::to_string(100.0 * t.maxBadShare) + " %";
}

ImageDifference compareImages(const render::Image& actual, const render::Image& expected,
                              const ImageTolerance& tolerance) {
  ImageDifference d;
  d.sameSize =
      actual.width == expected.width && actual.height == expected.height && actual.width > 0;
  if (!d.sameSize) return d;
  d.diff = render::Image(actual.width, actual.height);
  for (int y = 0; y < actual.height; ++y)
    for (int x = 0; x < actual.width; ++x) {
      const std::uint8_t* a = actual.at(x, y);
      const bool bad =
          !hasNearMatch(a, expected, x, y, tolerance.searchRadius, tolerance.channelThreshold) ||
          !hasNearMatch(expected.at(x, y), actual, x, y, tolerance.searchRadius,
                        tolerance.channelThreshold);
      std::uint8_t* out = d.diff.at(x, y);
      if (bad) {
        ++d.badPixels;
        out[0] = 255, out[1] = 0, out[2] = 0;
      } else {
        const int grey = (a[0] + a[1] + a[2]) / 3;
        out[0] = out[1] = out[2] = static_cast<std::uint8_t>(160 + grey * 95 / 255);
      }
    }
  d.badShare = double(d.badPixels) / (double(actual.width) * actual.height);
  return d;
}

}  // namespace weft::test
