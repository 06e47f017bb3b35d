#include <weft/render/Legend.h>

#include <algorithm>
#include <cmath>

namespace weft::render {

std::vector<LegendSwatch> contactLegendSwatches(int width, int height) {
  const float s = float(height) / 720.0f;
  const float margin = std::max(8.0f, std::round(24.0f * s)),
              border = std::max(1.0f, std::round(2.0f * s)),
              size = std::max(8.0f, std::round(16.0f * s)),
              gap = std::max(3.0f, std::round(8.0f * s));
  const float right = float(width) - margin;
  std::vector<LegendSwatch> out;
  float y = float(height) - margin;
  for (ContactBranch b : {ContactBranch::Slip, ContactBranch::Stick, ContactBranch::TakeOff}) {
    out.push_back({b, right - size, y - size, right, y, border});
    y -= size + 2.0f * border + gap;
  }
  return out;
}

const char* branchName(ContactBranch branch) {
  switch (branch) {
    case ContactBranch::TakeOff:
      return "take-off";
    case ContactBranch::Stick:
      return "stick";
    case ContactBranch::Slip:
      return "slip";
    case ContactBranch::None:
      break;
  }
  return "";
}

}  // namespace weft::render
