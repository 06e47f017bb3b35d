#pragma once
// Where benchmarks find the scenes they run: the working directory's assets/ (running from a
// checkout) first, else the source tree's assets/ compiled into the binary.

#include <string>

namespace weft::bench {

// `relative` below assets/, e.g. "scenes/sphere.json".
std::string assetFile(const std::string& relative);

}  // namespace weft::bench
