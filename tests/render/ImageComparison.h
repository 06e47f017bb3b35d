#pragma once
// The golden-image metric, as VTK and ITK regression tests do it: a pixel matches when some
// pixel within `searchRadius` of it in the other image differs by at most `channelThreshold`
// in every channel (checked both ways, so a missing or an extra thin line both count), and
// two images match when at most `maxBadShare` of their pixels do not.

#include <weft/render/Image.h>

#include <cstddef>
#include <string>

namespace weft::test {

struct ImageTolerance {
  int channelThreshold = 16;    // of 255
  double maxBadShare = 0.0025;  // 0.25 % of the pixels
  int searchRadius = 1;         // pixels
};

struct ImageDifference {
  bool sameSize = false;
  std::size_t badPixels = 0;
  double badShare = 1.0;
  render::Image diff;  // bad pixels red over a faded copy of the actual image
  bool matches(const ImageTolerance& t) const { return sameSize && badShare <= t.maxBadShare; }
  std::string describe(const ImageTolerance& t) const;
};

ImageDifference compareImages(const render::Image& actual, const render::Image& expected,
                              const ImageTolerance& tolerance = {});

}  // namespace weft::test
