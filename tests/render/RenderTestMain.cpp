// The render tests' main: GoogleTest plus `--bless`, which rewrites the golden images from this
// run's renders (equivalently WEFT_BLESS=1). Blessing is always on purpose and always reported.

#include "GoldenImage.h"

#include <gtest/gtest.h>

#include <cstring>

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--bless") == 0) weft::test::requestBless();
  return RUN_ALL_TESTS();
}
