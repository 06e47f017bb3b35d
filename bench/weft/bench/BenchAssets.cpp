#include "BenchAssets.h"

#include <filesystem>

namespace weft::bench {

std::string assetFile(const std::string& relative) {
  const std::string local = "assets/" + relative;
  if (std::filesystem::exists(local)) return local;
  return std::string(WEFT_ASSET_DIR) + "/" + relative;
}

}  // namespace weft::bench
