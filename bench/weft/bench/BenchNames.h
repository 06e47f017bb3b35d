#pragma once
// The benchmarks `weft bench NAME` runs (app/weft/BenchCommand.cpp dispatches on them, one
// run*Bench entry point each), in the order its usage and its errors list them.

#include <string>

namespace weft::bench {

inline constexpr const char* kBenchNames[] = {"forward", "backward",     "continuity",
                                              "contact", "applications", "render",
                                              "soak",    "distribution", "impact_zones"};

// "forward, backward, ..., render".
inline std::string benchNameList() {
  std::string list;
  for (const char* name : kBenchNames) list += (list.empty() ? "" : ", ") + std::string(name);
  return list;
}

}  // namespace weft::bench
