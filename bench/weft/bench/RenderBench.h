#pragma once
// `weft bench render` (RenderBench.cpp): headless drawing speed of a 48x48 cloth draped on a
// sphere, per overlay, and of a run rendered to PNG as `weft render` does it.

#include <weft/render/HeadlessContext.h>

#include <string>

namespace weft::bench {

struct RenderBenchOptions {
  bool quick = false;   // 10 timed frames per case instead of 100
  int runFrames = 200;  // states of the run rendered to PNG
  int width = 1280, height = 720;
  render::HeadlessBackend backend = render::HeadlessBackend::Auto;
};

struct RenderBenchSummary {
  std::string backend, glRenderer;
  double plainFramesPerSecond = 0.0;  // the draped cloth, no overlay
  int runFrames = 0;
  double runSeconds = 0.0, drawSeconds = 0.0, pngWaitSeconds = 0.0;
};

// Writes render.csv and render.md into `outDir` (staged: nothing is left there on failure).
// Throws render::ContextError when the backend cannot start.
RenderBenchSummary runRenderBench(const RenderBenchOptions& options, const std::string& outDir);

}  // namespace weft::bench
