#include "EditorBenchmark.h"

#include "EditorApp.h"
#include "EditorGl.h"
#include "EditorSession.h"

#include <weft/core/Error.h>
#include <weft/core/ProcessCpuTime.h>

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <thread>

#include <time.h>
#include <vector>

namespace weft::editor {
namespace {

using Clock = std::chrono::steady_clock;

// CPU time of the whole process (every thread: the UI, llvmpipe's rasterizer threads, a worker).
double processCpuMs() {
  return 1e3 * processCpuSeconds();
}

struct FrameTime {
  double wall = 0, cpu = 0;  // ms
};

// The Wind scene (assets/scenes/wind.json: a napkin hanging from two corners in wind) at the
// benchmark's resolution.
nlohmann::json windDocument(int grid, int steps) {
  nlohmann::json doc = nlohmann::json::parse(R"({
    "name": "editor-bench-wind",
    "time": { "dt": 0.0111, "steps": 30 },
    "gravity": [0, -9.8, 0],
    "solver": { "pd_iterations": 500, "pd_tolerance": 1e-4 },
    "cloths": [ {
      "mesh": { "grid": { "size": [1.0, 1.0], "resolution": [100, 100] },
                "transform": { "rotate_deg": [90, 0, 0], "translate": [0, 1.0, 0] } },
      "material": { "density": 0.2, "stretch": 1000.0, "bend": 0.0001 },
      "attachments": [ { "vertices": [0, 100], "kind": "fixed" } ]
    } ],
    "wind": { "direction": [0.2, 0, 1.0], "strength": 1.0, "frequency": 1.0, "phase": 0.0 }
  })");
  doc["time"]["steps"] = steps;
  doc["cloths"][0]["mesh"]["grid"]["resolution"] = {grid, grid};
  doc["cloths"][0]["attachments"][0]["vertices"] = {0, grid};
  return doc;
}

struct Summary {
  std::string mode;
  int frames = 0;
  double median = 0, p95 = 0, mean = 0, cpuMedian = 0;
};

Summary summarise(const std::string& mode, const std::vector<FrameTime>& times) {
  Summary s;
  s.mode = mode;
  s.frames = static_cast<int>(times.size());
  if (times.empty()) return s;
  std::vector<double> ms, cpu;
  for (const FrameTime& t : times) ms.push_back(t.wall), cpu.push_back(t.cpu);
  std::sort(ms.begin(), ms.end());
  std::sort(cpu.begin(), cpu.end());
  auto quantile = [&](double q) {
    // Nearest rank: the smallest time at or above which a fraction q of the frames lie.
    const std::size_t rank = static_cast<std::size_t>(std::ceil(q * double(ms.size())));
    return ms[std::min(ms.size() - 1, rank > 0 ? rank - 1 : 0)];
  };
  s.median = quantile(0.5);
  s.p95 = quantile(0.95);
  s.cpuMedian = cpu[std::min(cpu.size() - 1, (cpu.size() + 1) / 2 - 1)];
  double sum = 0;
  for (double v : ms) sum += v;
  s.mean = sum / double(ms.size());
  return s;
}

}  // namespace

int runEditorBenchmark(const EditorBenchmarkOptions& o, std::ostream& out) {
  EditorSession session("");
  if (!o.scene.empty())
    session.open(o.scene);
  else
    session.newDocument(windDocument(o.grid, o.steps));
  if (!session.document().valid())
    throw InputError(o.scene.empty() ? "bench" : o.scene, "-",
                     session.document().validationError());
  const int vertices = session.document().scene()->vertexCount();
  const int steps = o.scene.empty() ? o.steps : session.document().scene()->time.steps;

  std::unique_ptr<render::RenderContext> context =
      render::createHeadlessContext(o.width, o.height, o.backend, &out);
  const std::string backend = context->backendName();
  std::vector<std::pair<std::string, std::vector<FrameTime>>> modes;
  {
    EditorApp app(session, *context);
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(float(o.width), float(o.height));
    io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
    io.DeltaTime = 1.0f / 60.0f;
    auto timedFrame = [&] {
      const auto start = Clock::now();
      const double cpuStart = processCpuMs();
      app.frame();
      weftEditorGl.Finish();
      return FrameTime{std::chrono::duration<double, std::milli>(Clock::now() - start).count(),
                       processCpuMs() - cpuStart};
    };
    app.showTab(PanelTab::Inspect);            // the plots panel: the busiest UI while scrubbing
    for (int i = 0; i < 3; ++i) timedFrame();  // shaders, buffers, first layout
    session.frameCamera(float(app.viewportWidth()) / float(std::max(app.viewportHeight(), 1)));
    session.selection().set({vertices / 2});

    // Live: the viewport follows the newest state while the worker simulates.
    std::vector<FrameTime> live;
    const std::string error = session.timeline().simulate(steps);
    if (!error.empty()) throw InputError("bench", "-", error);
    while (session.cache().running() && static_cast<int>(live.size()) < o.frames) {
      session.playback().scrub(session.timeline().availableFrames() - 1,
                               session.timeline().availableFrames());
      live.push_back(timedFrame());
    }
    session.cache().wait();
    if (session.cache().status() != SimulationCache::Status::Done)
      throw InputError("bench", "-", "the simulation did not finish: " + session.cache().error());
    modes.emplace_back("live", std::move(live));

    // Scrub: a different cached state every frame, back and forth over the whole run.
    const int available = session.timeline().availableFrames();
    std::vector<FrameTime> scrub;
    for (int i = 0; i < o.frames; ++i) {
      const int period = std::max(2 * (available - 1), 1);
      const int k = i % period;
      session.playback().scrub(k < available ? k : period - k, available);
      scrub.push_back(timedFrame());
    }
    modes.emplace_back("scrub", std::move(scrub));

    // Still: the same state every frame (the UI and viewport redraw without new geometry).
    std::vector<FrameTime> still;
    for (int i = 0; i < o.frames; ++i) still.push_back(timedFrame());
    modes.emplace_back("still", std::move(still));
  }
  context.reset();

  std::vector<Summary> rows;
  for (const auto& [mode, ms] : modes) rows.push_back(summarise(mode, ms));
  std::ostringstream md;
  md << "Editor frame time: " << vertices << " cloth vertices, " << steps + 1 << " cached states, "
     << o.width << "x" << o.height << ", " << backend << ", " << std::thread::hardware_concurrency()
     << " hardware threads\n\n";
  md << "| mode | frames | median ms | p95 ms | mean ms | median fps | median CPU ms (all threads) "
        "|\n"
     << "| --- | --- | --- | --- | --- | --- | --- |\n";
  md << std::fixed << std::setprecision(1);
  for (const Summary& s : rows)
    md << "| " << s.mode << " | " << s.frames << " | " << s.median << " | " << s.p95 << " | "
       << s.mean << " | " << (s.median > 0 ? 1000.0 / s.median : 0.0) << " | " << s.cpuMedian
       << " |\n";
  out << md.str();
  if (!o.out.empty()) {
    std::filesystem::create_directories(o.out);
    std::ofstream csv(o.out + "/editor-bench.csv");
    csv << "mode,frame,ms,cpu_ms\n";
    for (const auto& [mode, times] : modes)
      for (std::size_t i = 0; i < times.size(); ++i)
        csv << mode << "," << i << "," << times[i].wall << "," << times[i].cpu << "\n";
    std::ofstream table(o.out + "/editor-bench.md");
    table << md.str();
    if (!csv || !table) throw InputError(o.out, "-", "cannot write the benchmark files");
    out << "wrote " << o.out << "/editor-bench.csv and editor-bench.md\n";
  }
  return 0;
}

}  // namespace weft::editor
