// `weft render SCENE|RUNDIR`: PNG frames of a scene (simulated first) or of a run folder,
// drawn headless (OSMesa, or EGL surfaceless where OSMesa is missing).

#include "CommandLine.h"
#include "Commands.h"
#include "SceneOverrideOption.h"
#include "SceneWarnings.h"

#include <weft/core/Error.h>
#include <weft/frames/RenderJob.h>
#include <weft/io/StagedDirectory.h>
#include <weft/output/RunFolder.h>
#include <weft/physics/Simulator.h>
#include <weft/render/RenderError.h>
#include <weft/scene/SceneLoader.h>

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>

extern char** environ;

namespace fs = std::filesystem;

namespace weft::cli {

namespace {

struct FrameRange {
  int first = 0;
  std::optional<int> last;  // empty: the last state
  int stride = 1;
};

// A:B:S, A:B or A; B may be left empty for "the last state" (e.g. 0::5).
FrameRange parseFrames(const CommandLine& cl) {
  FrameRange r;
  if (!cl.has("--frames")) return r;
  const std::string text = cl.value("--frames", "");
  auto bad = [&] {
    cl.fail("--frames", "expects A:B:S (first:last:stride, last may be empty), got '" + text + "'");
  };
  std::vector<std::string> parts;
  std::size_t begin = 0;
  for (std::size_t colon; (colon = text.find(':', begin)) != std::string::npos; begin = colon + 1)
    parts.push_back(text.substr(begin, colon - begin));
  parts.push_back(text.substr(begin));
  if (parts.size() > 3) bad();
  auto number = [&](const std::string& s) {
    char* end = nullptr;
    const long v = std::strtol(s.c_str(), &end, 10);
    if (s.empty() || *end != '\0' || v < 0 || v > 100000000) bad();
    return static_cast<int>(v);
  };
  r.first = number(parts[0]);
  if (parts.size() >= 2 && !parts[1].empty()) r.last = number(parts[1]);
  if (parts.size() == 1) r.last = r.first;
  if (parts.size() == 3) r.stride = number(parts[2]);
  if (r.stride < 1) cl.fail("--frames", "stride must be at least 1, got '" + text + "'");
  if (r.last && *r.last < r.first)
    cl.fail("--frames", "last frame comes before the first in '" + text + "'");
  return r;
}

void parseSize(const CommandLine& cl, int& width, int& height) {
  if (!cl.has("--size")) return;
  const std::string text = cl.value("--size", "");
  int w = 0, h = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%dx%d%c", &w, &h, &tail) != 2 || w < 16 || h < 16 || w > 8192 ||
      h > 8192)
    cl.fail("--size", "expects WxH with each side in [16, 8192], got '" + text + "'");
  width = w;
  height = h;
}

std::string findOnPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (!path) return "";
  const std::string all = path;
  std::size_t begin = 0;
  while (begin <= all.size()) {
    const std::size_t end = std::min(all.find(':', begin), all.size());
    const std::string dir = all.substr(begin, end - begin);
    const std::string candidate = (dir.empty() ? "." : dir) + "/" + program;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
    begin = end + 1;
  }
  return "";
}

// Runs ffmpeg on the committed frames; the video appears only when complete.
void writeVideo(const CommandLine& cl, const std::string& ffmpeg, const std::string& framesDir,
                const std::string& video, double fps) {
  const std::string partial =
      video + ".tmp-" + std::to_string(::getpid()) + fs::path(video).extension().string();
  char rate[32];
  std::snprintf(rate, sizeof rate, "%.6g", fps);
  std::vector<std::string> args = {ffmpeg, "-y", "-loglevel", "error", "-framerate", rate,
                                   "-pattern_type", "glob", "-i", framesDir + "/frame_*.png",
                                   // H.264 in yuv420p needs even sides.
                                   "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-pix_fmt", "yuv420p",
                                   partial};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  int status = 0;
  if (::posix_spawn(&pid, ffmpeg.c_str(), nullptr, nullptr, argv.data(), environ) != 0 ||
      ::waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::error_code ec;
    fs::remove(partial, ec);
    cl.fail("--video", "ffmpeg failed to write " + video);
  }
  std::error_code ec;
  fs::rename(partial, video, ec);
  if (ec) cl.fail("--video", "cannot move the video into " + video + ": " + ec.message());
}

}  // namespace

int renderCommand(const std::vector<std::string>& args) {
  CommandLine cl(
      args,
      {"--frames", "--size", "--camera", "--overlay", "--out", "--video", "--backend", "--set"},
      {"--wireframe", "--quiet"});
  if (cl.positional().size() != 1)
    cl.fail("SCENE|RUNDIR", "render takes exactly one scene file or run folder");
  const std::string input = cl.positional()[0];
  cl.setContext(input);

  RenderJob job;
  job.input = input;
  job.quiet = cl.has("--quiet");
  job.wireframe = cl.has("--wireframe");
  parseSize(cl, job.width, job.height);
  const std::string camera = cl.value("--camera", "auto");
  if (!render::parseNamedView(camera, job.view))
    cl.fail("--camera", "must be front, side, top or auto, got '" + camera + "'");
  const std::string overlay = cl.value("--overlay", "none");
  if (!parseOverlay(overlay, job.overlay))
    cl.fail("--overlay", "must be contacts, strain, speed or none, got '" + overlay + "'");
  const std::string backend = cl.value("--backend", "auto");
  if (!render::parseHeadlessBackend(backend, job.backend))
    cl.fail("--backend", "must be auto, osmesa or egl, got '" + backend + "'");
  const FrameRange range = parseFrames(cl);
  const std::string video = cl.value("--video", "");
  std::string ffmpeg;
  if (cl.has("--video")) {
    if (video.empty()) cl.fail("--video", "needs an output file name");
    ffmpeg = findOnPath("ffmpeg");
    // Said before any work: a video was asked for and cannot be made here.
    if (ffmpeg.empty())
      cl.fail("--video",
              "ffmpeg is not available on PATH (Debian package: ffmpeg); drop --video to write PNG "
              "frames only");
  }

  const bool fromRun = isRunFolder(input);
  if (!fs::exists(input)) cl.fail("SCENE|RUNDIR", "no such file or folder");
  if (fromRun && cl.has("--set"))
    cl.fail("--set", "applies to a scene file; a run folder is rendered as it was simulated");

  RunFolder run;
  if (fromRun) {
    run = loadRunFolder(input);
  } else {
    run.scene = loadScene(input, parseOverrides(cl));
    run.path = input;
  }
  printSceneWarnings(run.scene);
  const int available = fromRun ? int(run.states.size()) - 1 : run.scene.time.steps;
  const int last = range.last.value_or(available);
  if (range.first > available || last > available)
    cl.fail("--frames", "frame " + std::to_string(std::max(range.first, last)) +
                            " is past the last state " + std::to_string(available) +
                            (fromRun ? " of the run" : " (the scene's time.steps)"));
  for (int s = range.first; s <= last; s += range.stride) job.frames.push_back(s);

  const std::string outDir =
      cl.value("--out", fromRun ? (fs::path(input) / "frames").lexically_normal().string()
                                : "out/" + run.scene.name + "-frames");
  StagedDirectory out(outDir);  // fails early on an unusable --out, before simulating

  if (!fromRun) {
    // Simulate only as far as the last frame asked for; state 0 alone needs no simulation.
    const int steps = job.frames.back();
    if (steps == 0) {
      run.states = {buildClothModel(run.scene).rest.vertices};
    } else {
      Simulator sim(run.scene);
      Trajectory trajectory;
      const int every = std::max(1, steps / 10);
      sim.run(steps, trajectory, [&](const StepStats& s) {
        if (!job.quiet && s.step % every == 0)
          std::fprintf(stderr, "\rsimulate step %d/%d", s.step, steps);
      });
      if (!job.quiet) std::fprintf(stderr, "\n");
      run.states = std::move(trajectory.positions);
    }
  }

  const ClothModel model = buildClothModel(run.scene);
  RenderReport report;
  try {
    report = renderFrames(run.scene, model, run.states, run.contacts, job, out.path());
  } catch (const render::ContextError& e) {
    // An environment problem the user fixes by installing a package or picking a backend.
    cl.fail("--backend " + backend,
            e.what() + std::string(" (install libosmesa6, or libegl1 with libegl-mesa0)"));
  } catch (const render::ImageFileError& e) {
    cl.fail("--out", e.what());
  }
  for (const std::string& w : report.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  out.commit();

  if (!video.empty()) {
    const double fps = std::clamp(1.0 / (run.scene.time.dt * range.stride), 1.0, 240.0);
    writeVideo(cl, ffmpeg, outDir, video, fps);
  }
  std::printf(
      "render: %s: %d frames %dx%d, %s overlay, %s (%s), %.2f s (%.1f frames/s, %.1f drawing) -> "
      "%s%s%s\n",
      run.scene.name.c_str(), report.frames, job.width, job.height, overlayName(job.overlay),
      report.backend.c_str(), report.glRenderer.c_str(), report.totalSeconds,
      report.totalSeconds > 0 ? report.frames / report.totalSeconds : 0.0,
      report.renderSeconds > 0 ? report.frames / report.renderSeconds : 0.0, outDir.c_str(),
      video.empty() ? "" : ", ", video.c_str());
  return 0;
}

}  // namespace weft::cli
