#pragma once
// How a frame is drawn (colours, wireframe, ground, legend), as opposed to what it shows.

#include <weft/render/RenderScene.h>

namespace weft::render {

struct RenderStyle {
  Rgb background{0.94f, 0.95f, 0.97f};
  Rgb clothFront{0.92f, 0.52f, 0.24f};
  Rgb clothBack{0.32f, 0.52f, 0.82f};
  // Cloth colours under the contact overlay: muted so the branch colours stand out.
  Rgb overlayFront{0.80f, 0.78f, 0.74f};
  Rgb overlayBack{0.62f, 0.66f, 0.72f};
  Rgb obstacle{0.70f, 0.72f, 0.76f};
  Rgb ground{0.84f, 0.85f, 0.87f};
  Rgb grid{0.55f, 0.57f, 0.62f};
  Rgb wire{0.12f, 0.12f, 0.14f};
  Rgb fixedPoint{0.12f, 0.12f, 0.14f};
  Rgb handlePoint{0.10f, 0.65f, 0.30f};
  Rgb targetPoint{0.60f, 0.20f, 0.75f};
  Rgb arrow{0.45f, 0.10f, 0.55f};
  bool wireframe = false;
  bool groundGrid = true;  // a grid on each plane obstacle, or under the scene when there is none
  bool legend = true;      // colour bar for scalars, swatches for contact branches
  // See-through views, for a garment on a body: the cloth drawn translucent (1 = opaque; markers
  // and contacts behind it then show), and the obstacles drawn once more over everything,
  // translucent, so what a garment hides shows through it.
  float clothOpacity = 1.0f;
  bool obstaclesInFront = false;
  float pointSize = 0.0f;  // marker diameter in pixels; 0 scales with the image height
  float lineWidth = 0.0f;  // curve width in pixels; 0 scales with the image height
};

}  // namespace weft::render
