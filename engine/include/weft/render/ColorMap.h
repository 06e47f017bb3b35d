#pragma once
// Colour maps for per-vertex scalars, and the fixed colours of the contact branches.

#include <weft/render/RenderScene.h>

#include <cstdint>
#include <vector>

namespace weft::render {

// Colour at t in [0, 1] (clamped).
Rgb colorMapColor(ColorMapKind map, float t);

// `size` RGB8 samples from t = 0 to t = 1, for a GL texture.
std::vector<std::uint8_t> colorMapTable(ColorMapKind map, int size = 256);

// Exact, unlit colours of contact nodes: distinct in every channel combination so a test can
// tell them apart pixel by pixel. None has no colour (such nodes are not drawn).
Rgb branchColor(ContactBranch branch);

struct RenderStyle;
// The marker colour of pin group `group` (the scene's fixed attachments, cloths in order): the
// style's fixedPoint for the first, then brown, teal, pink, olive and grey, repeating; apart from
// the branch colours above, the cloth's orange and blue, handles' green, targets' purple and the
// editor's white selection.
Rgb pinGroupColor(int group, const RenderStyle& style);

}  // namespace weft::render
