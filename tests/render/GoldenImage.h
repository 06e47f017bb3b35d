#pragma once
// Comparing renders with the golden images in tests/golden/. A mismatch writes the actual,
// expected and diff images to the build's golden-output folder. A missing golden fails; only
// an explicit bless (--bless or WEFT_BLESS=1) writes goldens, and it says so.

#include "ImageComparison.h"

#include <weft/render/Image.h>

#include <gtest/gtest.h>

#include <string>

namespace weft::test {

void requestBless();
bool blessRequested();  // --bless was given or WEFT_BLESS=1

// `name` without extension, e.g. "draped_cloth_sphere".
::testing::AssertionResult matchesGolden(const std::string& name, const render::Image& actual,
                                         const ImageTolerance& tolerance = {});

}  // namespace weft::test
