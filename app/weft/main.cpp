// `weft`: the command-line face of the engine. Exit codes: 0 success, 2 bad input or usage,
// 3 numerical failure (the contract of the product spec).

#include "../process/PassiveOpenMpWait.h"
#include "BuildInfo.h"
#include "Commands.h"

#include <weft/bench/BuildRecord.h>
#include <weft/core/Error.h>

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

namespace {

const char* kUsage =
    "usage: weft <verb> [arguments]\n"
    "  simulate SCENE [--steps N] [--out DIR] [--set PATH=VALUE ...] [--threads N] [--quiet]\n"
    "  render SCENE|RUNDIR [--frames A:B:S] [--size WxH] [--camera front|side|top|auto]\n"
    "         [--overlay contacts|strain|speed|none] [--wireframe] [--out DIR] [--video FILE.mp4]\n"
    "         [--backend auto|osmesa|egl] [--set PATH=VALUE ...] [--quiet]\n"
    "  bench NAME [--out DIR] [--quick]        (NAME: forward, backward, continuity, contact, "
    "render)\n"
    "  gradcheck SCENE [--param PATH ...] [--eps E] [--json] [--set PATH=VALUE ...]\n"
    "         [--backward gmres|fixed_point|direct] [--forward-tolerance T] [--backward-tolerance "
    "T]\n"
    "  optimize SCENE [--method lbfgsb|cmaes|es1p1|adam] [--seed S] [--budget STEPS] [--out DIR]\n"
    "         [--max-evaluations N] [--learning-rate R] [--first-step L]\n"
    "         [--min-curvature-step L] [--set PATH=VALUE ...]\n"
    "  landscape SCENE --param A [--param B] [--grid N] [--range PATH=LO:HI ...] [--out DIR]\n"
    "         [--set PATH=VALUE ...] [--threads N] [--quiet]\n"
    "  --version                                 (the commit this build was made from)\n"
    "Exit codes: 0 success, 2 bad input or usage, 3 numerical failure.\n";

}  // namespace

int main(int argc, char** argv) {
  weft::process::preferPassiveOpenMpWait(argv);
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    std::fputs(kUsage, args.empty() ? stderr : stdout);
    return args.empty() ? 2 : 0;
  }
  if (args[0] == "--version") {
    std::printf("weft %s, %s\n", WEFT_VERSION,
                weft::bench::describeBuild(weft::cli::buildInfoJson()).c_str());
    return 0;
  }
  const std::string verb = args[0];
  args.erase(args.begin());
  try {
    if (verb == "simulate") return weft::cli::simulateCommand(args);
    if (verb == "render") return weft::cli::renderCommand(args);
    if (verb == "bench") return weft::cli::benchCommand(args);
    if (verb == "gradcheck") return weft::cli::gradcheckCommand(args);
    if (verb == "optimize") return weft::cli::optimizeCommand(args);
    if (verb == "landscape") return weft::cli::landscapeCommand(args);
    std::fprintf(stderr, "error: weft: %s: unknown verb\n%s", verb.c_str(), kUsage);
    return 2;
  } catch (const weft::InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const weft::NumericalError& e) {
    std::fprintf(stderr, "error: numerical failure: %s\n", e.what());
    return 3;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "error: out of memory\n");
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: internal: %s\n", e.what());
    return 1;
  }
}
