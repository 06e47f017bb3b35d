#pragma once
// Renders the states of a run to PNG frames headless: the work behind `weft render`, shared
// with the render benchmark.

#include <weft/model/ClothModel.h>
#include <weft/output/RunFolder.h>
#include <weft/render/Camera.h>
#include <weft/render/HeadlessContext.h>
#include <weft/scene/Scene.h>

#include <string>
#include <vector>

namespace weft {

enum class Overlay { None, Contacts, Strain, Speed };

// "none", "contacts", "strain", "speed"; returns false for anything else.
bool parseOverlay(const std::string& text, Overlay& overlay);
const char* overlayName(Overlay overlay);

struct RenderJob {
  std::vector<int> frames;  // state indices to render, in order
  int width = 1280, height = 720;
  render::NamedView view = render::NamedView::Auto;
  Overlay overlay = Overlay::None;
  bool wireframe = false;
  render::HeadlessBackend backend = render::HeadlessBackend::Auto;
  std::string input;  // what is rendered, for render.json
  bool quiet = false;
};

struct RenderReport {
  int frames = 0;
  double renderSeconds = 0.0;  // drawing and reading back
  double writeSeconds = 0.0;   // waiting for PNG encoding (on background threads) beyond drawing
  double totalSeconds = 0.0;   // including context and shader set-up
  std::string backend, glVersion, glRenderer;
  float low = 0.0f, high = 0.0f;  // colour-map range of a scalar overlay
  std::vector<std::string> warnings;
};

// Renders `job.frames` of `states` into `folder` as frame_NNNNNN.png plus render.json. The
// camera frames every rendered state at once, so it holds still through the sequence.
// Throws render::ContextError when no headless OpenGL exists, ImageFileError on write errors.
RenderReport renderFrames(const Scene& scene, const ClothModel& model,
                          const std::vector<NodeMatrix>& states, const ContactRecord& contacts,
                          const RenderJob& job, const std::string& folder);

std::string frameFileName(int state);

}  // namespace weft
