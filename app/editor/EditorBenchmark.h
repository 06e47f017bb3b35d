#pragma once
// `weft-editor --bench`: how long one editor UI frame takes on a ~10k-vertex cloth, drawn
// headless through OSMesa (or EGL) with the whole UI (panels, timeline, viewport), in three
// modes: `live` while the simulation runs on its worker thread and the viewport follows the
// newest state; `scrub` through the finished cache, a different state every frame (the worst
// case for the viewport: new geometry each time); `still` on one state (the UI alone). A frame
// is timed from its start until the GL work is finished (glFinish), in wall time and in CPU
// time of the whole process (every thread: the UI, the software rasterizer's threads, and in
// `live` the simulation), which a machine shared with other jobs inflates far less. Prints a
// Markdown table and, with an output folder, writes editor-bench.csv (every frame) and
// editor-bench.md.
// The editor binary owns this mode, not `weft bench`: the `weft` tool does not link ImGui.

#include <weft/render/HeadlessContext.h>

#include <iosfwd>
#include <string>

namespace weft::editor {

struct EditorBenchmarkOptions {
  std::string scene;  // a scene file; empty: the Wind napkin at `grid` x `grid` quads
  int grid = 100;     // 100 x 100 quads = 10201 vertices
  int steps = 30;     // states cached for scrubbing: steps + 1
  int frames = 240;   // UI frames measured per mode
  int width = 1280, height = 720;
  std::string out;  // folder for the CSV and Markdown ("" = print only)
  render::HeadlessBackend backend = render::HeadlessBackend::Auto;
};

// Returns the exit code (0, or 2 on bad input); the table goes to `out`.
int runEditorBenchmark(const EditorBenchmarkOptions& options, std::ostream& out);

}  // namespace weft::editor
