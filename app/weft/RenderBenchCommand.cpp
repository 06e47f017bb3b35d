// `weft bench render`: its options; the benchmark is bench::runRenderBench.

#include "CommandLine.h"
#include "Commands.h"

#include <weft/bench/RenderBench.h>
#include <weft/render/RenderError.h>

#include <cstdio>

namespace weft::cli {

int renderBenchmark(const std::vector<std::string>& args) {
  CommandLine cl(args, {"--out", "--frames", "--size", "--backend"}, {"--quick"});
  cl.setContext("bench render");
  bench::RenderBenchOptions options;
  options.quick = cl.has("--quick");
  options.runFrames = cl.integer("--frames", options.quick ? 20 : 200, 1, 100000);
  if (cl.has("--size")) {
    const std::string text = cl.value("--size", "");
    char tail = 0;
    if (std::sscanf(text.c_str(), "%dx%d%c", &options.width, &options.height, &tail) != 2 ||
        options.width < 16 || options.height < 16 || options.width > 8192 || options.height > 8192)
      cl.fail("--size", "expects WxH with each side in [16, 8192], got '" + text + "'");
  }
  const std::string backendName = cl.value("--backend", "auto");
  if (!render::parseHeadlessBackend(backendName, options.backend))
    cl.fail("--backend", "must be auto, osmesa or egl, got '" + backendName + "'");
  const std::string outDir = cl.value("--out", "out/bench-render");
  bench::RenderBenchSummary s;
  try {
    s = bench::runRenderBench(options, outDir);
  } catch (const render::ContextError& e) {
    cl.fail("--backend " + backendName, e.what());
  }
  std::printf(
      "bench render: %dx%d %s: 48x48 cloth on a sphere %.1f frames/s; %d-frame run to PNG %.2f s "
      "(%.2f drawing, %.2f waiting for PNG) -> %s\n",
      options.width, options.height, s.backend.c_str(), s.plainFramesPerSecond, s.runFrames,
      s.runSeconds, s.drawSeconds, s.pngWaitSeconds, outDir.c_str());
  return 0;
}

}  // namespace weft::cli
