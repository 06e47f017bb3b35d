#pragma once
// The verbs of the `weft` command-line tool. Each returns the process exit code and throws
// InputError / NumericalError for main() to report.

#include <string>
#include <vector>

namespace weft::cli {

int simulateCommand(const std::vector<std::string>& args);
int benchCommand(const std::vector<std::string>& args);
int renderCommand(const std::vector<std::string>& args);
// `weft gradcheck` (GradcheckCommand.cpp): adjoint vs finite-difference gradient of the task loss.
int gradcheckCommand(const std::vector<std::string>& args);
// `weft gradient` (GradientCommand.cpp): the task loss's gradient as an optimiser gets it, with
// its error estimate.
int gradientCommand(const std::vector<std::string>& args);
// `weft optimize` (OptimizeCommand.cpp): minimises the task loss over the task's parameters.
int optimizeCommand(const std::vector<std::string>& args);
// `weft landscape` (LandscapeCommand.cpp): the task loss on a grid over one or two parameters.
int landscapeCommand(const std::vector<std::string>& args);
// `weft sweep` (SweepCommand.cpp): one simulation per combination of --set-grid values.
int sweepCommand(const std::vector<std::string>& args);
// `weft bench render` (RenderBenchCommand.cpp; the benchmark is bench/weft/bench/RenderBench).
int renderBenchmark(const std::vector<std::string>& args);

}  // namespace weft::cli
