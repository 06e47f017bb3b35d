#pragma once
// Where the renderer draws the contact branches' swatches: the lower right corner of the image,
// one per branch from the bottom up (slip, stick, take-off), sized for 720 rows and scaled with
// the image (with floors, so they stay readable in small images). The renderer has no text;
// callers that label the swatches (the editor's viewport) place their labels by this layout.

#include <weft/render/RenderScene.h>

#include <vector>

namespace weft::render {

struct LegendSwatch {
  ContactBranch branch;
  float left, top, right, bottom;  // image pixels from the top-left corner, the colour inside
  float border;                    // the dark frame's width around it
};

std::vector<LegendSwatch> contactLegendSwatches(int width, int height);

// What a branch is called in legends: "take-off", "stick", "slip" ("" for none).
const char* branchName(ContactBranch branch);

}  // namespace weft::render
