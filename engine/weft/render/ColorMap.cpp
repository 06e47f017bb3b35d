#include <weft/render/ColorMap.h>
#include <weft/render/RenderStyle.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace weft::render {
namespace {

// Perceptually ordered control points, evenly spaced in t. Sequential: matplotlib's viridis
// sampled at t = 0, 0.1, ..., 1. Diverging: Moreland's cool-warm at t = 0, 0.25, ..., 1.
constexpr std::array<std::array<float, 3>, 11> kSequential = {{{0.267f, 0.005f, 0.329f},
                                                               {0.283f, 0.141f, 0.458f},
                                                               {0.254f, 0.265f, 0.530f},
                                                               {0.207f, 0.372f, 0.553f},
                                                               {0.164f, 0.471f, 0.558f},
                                                               {0.128f, 0.567f, 0.551f},
                                                               {0.135f, 0.659f, 0.518f},
                                                               {0.267f, 0.749f, 0.441f},
                                                               {0.478f, 0.821f, 0.318f},
                                                               {0.741f, 0.873f, 0.150f},
                                                               {0.993f, 0.906f, 0.144f}}};
constexpr std::array<std::array<float, 3>, 5> kDiverging = {{{0.230f, 0.299f, 0.754f},
                                                             {0.552f, 0.690f, 0.996f},
                                                             {0.865f, 0.865f, 0.865f},
                                                             {0.958f, 0.604f, 0.482f},
                                                             {0.706f, 0.016f, 0.150f}}};

template <std::size_t N>
Rgb interpolate(const std::array<std::array<float, 3>, N>& points, float t) {
  const float x = std::clamp(t, 0.0f, 1.0f) * static_cast<float>(N - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(x), N - 2);
  const float f = x - static_cast<float>(i);
  const Rgb a(points[i][0], points[i][1], points[i][2]),
      b(points[i + 1][0], points[i + 1][1], points[i + 1][2]);
  return (1.0f - f) * a + f * b;
}

}  // namespace

Rgb colorMapColor(ColorMapKind map, float t) {
  if (!std::isfinite(t)) t = 0.0f;
  return map == ColorMapKind::Sequential ? interpolate(kSequential, t) : interpolate(kDiverging, t);
}

std::vector<std::uint8_t> colorMapTable(ColorMapKind map, int size) {
  std::vector<std::uint8_t> table(static_cast<std::size_t>(size) * 3);
  for (int i = 0; i < size; ++i) {
    const Rgb c = colorMapColor(map, size > 1 ? float(i) / float(size - 1) : 0.0f);
    for (int k = 0; k < 3; ++k)
      table[3 * i + k] =
          static_cast<std::uint8_t>(std::lround(std::clamp(c[k], 0.0f, 1.0f) * 255.0f));
  }
  return table;
}

Rgb pinGroupColor(int group, const RenderStyle& style) {
  static const Rgb kGroups[] = {{0.55f, 0.33f, 0.12f},
                                {0.00f, 0.50f, 0.50f},
                                {0.90f, 0.40f, 0.70f},
                                {0.45f, 0.50f, 0.05f},
                                {0.50f, 0.50f, 0.50f}};
  if (group <= 0) return style.fixedPoint;
  return kGroups[(group - 1) % 5];
}

Rgb branchColor(ContactBranch branch) {
  switch (branch) {
    case ContactBranch::TakeOff:
      return {0.0f, 0.6f, 1.0f};  // blue: separating
    case ContactBranch::Stick:
      return {0.9f, 0.0f, 0.1f};  // red: static friction
    case ContactBranch::Slip:
      return {1.0f, 0.8f, 0.0f};  // yellow: sliding friction
    case ContactBranch::None:
      break;
  }
  return {0.0f, 0.0f, 0.0f};
}

}  // namespace weft::render
