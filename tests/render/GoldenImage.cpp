#include "GoldenImage.h"

#include <weft/render/RenderError.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>

namespace fs = std::filesystem;

namespace weft::test {
namespace {

bool blessFlag = false;

}  // namespace

void requestBless() {
  blessFlag = true;
}

bool blessRequested() {
  const char* env = std::getenv("WEFT_BLESS");
  return blessFlag || (env && std::string(env) == "1");
}

::testing::AssertionResult matchesGolden(const std::string& name, const render::Image& actual,
                                         const ImageTolerance& tolerance) {
  const std::string golden = std::string(WEFT_GOLDEN_DIR) + "/" + name + ".png";
  if (blessRequested()) {
    render::writePng(golden, actual);
    std::cout << "[ BLESSED  ] " << golden << " rewritten from this run\n";
    return ::testing::AssertionSuccess();
  }
  const std::string outDir = WEFT_RENDER_TEST_OUTPUT;
  fs::create_directories(outDir);
  const std::string actualFile = outDir + "/" + name + ".actual.png";
  if (!fs::exists(golden)) {
    render::writePng(actualFile, actual);
    return ::testing::AssertionFailure()
           << "missing golden " << golden << "; this run's image is " << actualFile
           << ". Create it on purpose with --bless or WEFT_BLESS=1.";
  }
  const render::Image expected = render::readPng(golden);
  const ImageDifference d = compareImages(actual, expected, tolerance);
  if (d.matches(tolerance)) return ::testing::AssertionSuccess();
  render::writePng(actualFile, actual);
  render::writePng(outDir + "/" + name + ".expected.png", expected);
  if (d.sameSize) render::writePng(outDir + "/" + name + ".diff.png", d.diff);
  return ::testing::AssertionFailure() << name << ": " << d.describe(tolerance) << "; see "
                                       << outDir << "/" << name << ".{actual,expected,diff}.png";
}

}  // namespace weft::test
