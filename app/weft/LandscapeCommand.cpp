// `weft landscape SCENE --param A [--param B] [--grid N] [--range PATH=LO:HI ...] [--out DIR]
//                       [--set PATH=VALUE ...] [--threads N] [--quiet]`
// Evaluates the scene's task loss (forward runs only, no gradients) on an N x N grid over two
// parameters, or on N points over one (DiffCloth Fig. 3). Each parameter's default range is
// [0.5, 1.5] x its value in the scene (or value -1 .. value +1 when the value is 0); --range
// overrides it. Writes, into DIR (default out/landscape-<scene name>), staged so that a failed
// run never replaces a good folder:
//   landscape.csv  <A>,<B>,loss  (or <A>,loss) one row per grid point, A varying slowest
//   landscape.png  heat map of the loss (log colour scale when every loss is > 0) with the
//                  scene's own point marked; a line plot for one parameter (gnuplot; skipped,
//                  with a note, without it)

#include "CommandLine.h"
#include "Commands.h"
#include "SceneOverrideOption.h"
#include "SceneWarnings.h"

#include <weft/core/Error.h>
#include <weft/diff/ForwardPass.h>
#include <weft/diff/ParameterSet.h>
#include <weft/diff/TaskLoss.h>
#include <weft/distributed/WorkDistributor.h>
#include <weft/io/StagedDirectory.h>
#include <weft/scene/SceneLoader.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace weft::cli {

int applyThreads(const CommandLine& cl);  // SimulateCommand.cpp

namespace {

constexpr int kDefaultGrid = 11;
constexpr int kMaxGrid = 1001;

struct Range {
  double lo = 0.0, hi = 0.0;
};

// Parses "PATH=LO:HI" into the map; every problem names the option and its value.
void parseRange(const std::string& file, const std::string& text,
                std::map<std::string, Range>& ranges) {
  const std::string where = "--range " + text;
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) throw InputError(file, where, "expected PATH=LO:HI");
  const std::string path = text.substr(0, eq);
  const std::string bounds = text.substr(eq + 1);
  // The separator is the first ':' after the first character, so that a negative LO still parses.
  const auto colon = bounds.find(':', 1);
  if (colon == std::string::npos) throw InputError(file, where, "expected PATH=LO:HI");
  Range r;
  try {
    std::size_t used = 0;
    const std::string lo = bounds.substr(0, colon), hi = bounds.substr(colon + 1);
    r.lo = std::stod(lo, &used);
    if (used != lo.size()) throw std::invalid_argument(lo);
    r.hi = std::stod(hi, &used);
    if (used != hi.size()) throw std::invalid_argument(hi);
  } catch (const std::exception&) {
    throw InputError(file, where, "LO and HI must be numbers");
  }
  if (!std::isfinite(r.lo) || !std::isfinite(r.hi) || !(r.lo < r.hi))
    throw InputError(file, where, "needs finite LO < HI");
  if (ranges.count(path)) throw InputError(file, where, "range given twice for '" + path + "'");
  ranges[path] = r;
}

std::vector<double> gridValues(const Range& r, int n) {
  std::vector<double> v(n);
  for (int i = 0; i < n; ++i) v[i] = i == n - 1 ? r.hi : r.lo + (r.hi - r.lo) * i / (n - 1);
  return v;
}

std::string pointName(const ParameterSet& parameters, const std::vector<double>& values) {
  std::string s;
  for (int i = 0; i < parameters.size(); ++i) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.10g", values[i]);
    s += (i ? ", " : "") + parameters[i].path + "=" + buf;
  }
  return s;
}

// gnuplot-safe single-quoted text.
std::string quoted(std::string s) {
  std::string out;
  for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return "'" + out + "'";
}

bool plotLandscape(const std::string& png, const std::string& title, const ParameterSet& parameters,
                   const std::vector<std::vector<double>>& axes, const std::vector<double>& losses,
                   const std::vector<double>& scenePoint, std::string& reason) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
    reason = "gnuplot is not installed (apt-get install gnuplot-nox); no plot written";
    return false;
  }
  const bool logScale = std::all_of(losses.begin(), losses.end(), [](double l) { return l > 0.0; });
  const std::string script = png + ".gp";
  {
    std::ofstream gp(script);
    gp.precision(17);
    gp << "set terminal pngcairo size 900,700 noenhanced\n"
       << "set output " << quoted(png) << "\n"
       << "set title " << quoted(title) << "\n"
       << "set xlabel " << quoted(parameters[0].path) << "\n";
    if (parameters.size() == 1) {
      gp << "set ylabel 'loss'\nset grid\nset key top right\n";
      if (logScale) gp << "set logscale y\nset format y '%.0e'\n";
      gp << "set arrow from " << scenePoint[0] << ", graph 0 to " << scenePoint[0]
         << ", graph 1 nohead dashtype 2 lc rgb 'red'\n";
      gp << "plot '-' using 1:2 with linespoints title 'task loss', '-' using 1:2 with points pt 7 "
            "ps 1.5 "
            "lc rgb 'red' title 'scene value'\n";
      for (std::size_t i = 0; i < losses.size(); ++i) gp << axes[0][i] << " " << losses[i] << "\n";
      gp << "e\n";
      // The scene's own value on the curve when it is a grid point; otherwise only the dashed line.
      for (std::size_t i = 0; i < losses.size(); ++i)
        if (std::abs(axes[0][i] - scenePoint[0]) <= 1e-12 * std::max(1.0, std::abs(scenePoint[0])))
          gp << axes[0][i] << " " << losses[i] << "\n";
      gp << "e\n";
    } else {
      const std::size_t n0 = axes[0].size(), n1 = axes[1].size();
      const double dx = (axes[0].back() - axes[0].front()) / (n0 - 1);
      const double dy = (axes[1].back() - axes[1].front()) / (n1 - 1);
      gp << "set ylabel " << quoted(parameters[1].path) << "\n"
         << "set cblabel " << quoted(logScale ? "task loss (log scale)" : "task loss") << "\n"
         << "set xrange [" << axes[0].front() - dx / 2 << ":" << axes[0].back() + dx / 2 << "]\n"
         << "set yrange [" << axes[1].front() - dy / 2 << ":" << axes[1].back() + dy / 2 << "]\n"
         << "set palette rgbformulae 33,13,10\nset key bottom right opaque box\n";
      if (logScale) {
        // A loss of ~0 at an exact match (1e-18) would squash the rest of the map: the colour
        // scale spans at most ten decades below the largest loss.
        const double top = *std::max_element(losses.begin(), losses.end());
        const double bottom =
            std::max(*std::min_element(losses.begin(), losses.end()), 1e-10 * top);
        gp << "set logscale cb\nset format cb '%.0e'\nset cbrange [" << bottom << ":" << top
           << "]\n";
      }
      char label[160];
      std::snprintf(label, sizeof label, "scene value (%.6g, %.6g)", scenePoint[0], scenePoint[1]);
      gp << "plot '-' using 1:2:3 with image notitle, '-' using 1:2 with points pt 2 ps 2.5 lw 3 "
            "lc rgb 'black' title "
         << quoted(label) << "\n";
      for (std::size_t j = 0; j < n1; ++j) {
        for (std::size_t i = 0; i < n0; ++i)
          gp << axes[0][i] << " " << axes[1][j] << " " << losses[i * n1 + j] << "\n";
        gp << "\n";
      }
      gp << "e\n" << scenePoint[0] << " " << scenePoint[1] << "\ne\n";
    }
  }
  const int rc = std::system(("gnuplot " + quoted(script) + " 2>/dev/null").c_str());
  std::remove(script.c_str());
  if (rc != 0) {
    reason = "gnuplot failed";
    return false;
  }
  return true;
}

}  // namespace

int landscapeCommand(const std::vector<std::string>& args) {
  CommandLine cl(args, {"--param", "--grid", "--range", "--out", "--set", "--threads"},
                 {"--quiet"});
  if (cl.positional().size() != 1) cl.fail("SCENE", "landscape takes exactly one scene file");
  const std::string file = cl.positional()[0];
  cl.setContext(file);
  applyThreads(cl);
  const std::vector<std::string> paths = cl.values("--param");
  if (paths.empty() || paths.size() > 2)
    cl.fail("--param", "give one or two parameters (--param A --param B)");
  if (paths.size() == 2 && paths[0] == paths[1])
    cl.fail("--param", "the two parameters must differ");
  if (cl.has("--grid")) {
    const std::string g = cl.value("--grid", "");
    char* end = nullptr;
    const long v = std::strtol(g.c_str(), &end, 10);
    if (g.empty() || *end != '\0' || v < 2 || v > kMaxGrid)
      cl.fail("--grid",
              "must be a whole number in [2, " + std::to_string(kMaxGrid) + "], got '" + g + "'");
  }
  const int grid = cl.integer("--grid", kDefaultGrid, 2, kMaxGrid);
  std::map<std::string, Range> ranges;
  for (const std::string& r : cl.values("--range")) parseRange(file, r, ranges);
  for (const auto& [path, r] : ranges)
    if (std::find(paths.begin(), paths.end(), path) == paths.end())
      throw InputError(file, "--range " + path, "is not one of the --param paths");

  const Scene scene = loadScene(file, parseOverrides(cl));
  printSceneWarnings(scene);
  if (!scene.task)
    throw InputError(file, "task", "the scene has no task; landscape needs task.loss");
  const ParameterSet parameters = ParameterSet::fromPaths(scene, paths);
  const TaskLoss loss(scene);
  const Eigen::VectorXd sceneValues = parameters.values(scene);

  std::vector<std::vector<double>> axes;
  for (int p = 0; p < parameters.size(); ++p) {
    const std::string& path = parameters[p].path;
    Range r;
    if (ranges.count(path)) {
      r = ranges[path];
    } else {
      const double v = sceneValues[p];
      r = v == 0.0 ? Range{-1.0, 1.0}
                   : Range{std::min(0.5 * v, 1.5 * v), std::max(0.5 * v, 1.5 * v)};
    }
    axes.push_back(gridValues(r, grid));
  }

  const std::string outDir = cl.value("--out", "out/landscape-" + scene.name);
  // Rank 0 alone writes (under mpirun every rank runs this command); it fails early on an
  // unusable --out, before simulating.
  std::optional<StagedDirectory> out;
  if (launchRank() == 0) out.emplace(outDir);

  bool quiet = cl.has("--quiet");
  const std::size_t total = parameters.size() == 1 ? grid : static_cast<std::size_t>(grid) * grid;
  std::vector<double> losses;
  losses.reserve(total);
  std::ostringstream csv;
  for (int p = 0; p < parameters.size(); ++p) csv << parameters[p].path << ",";
  csv << "loss\n";
  csv.precision(17);
  int unconverged = 0;
  double best = HUGE_VAL;
  std::vector<double> bestPoint;
  const auto start = std::chrono::steady_clock::now();
  const auto pointAt = [&](std::size_t k) {
    return parameters.size() == 1 ? std::vector<double>{axes[0][k]}
                                  : std::vector<double>{axes[0][k / grid], axes[1][k % grid]};
  };
  // The grid points are work items (serial, or over MPI's ranks): each gives its loss and the
  // forward steps that stopped above tolerance.
  WorkDistributor& workers = processWorkers();
  if (!workers.isRoot()) quiet = true;
  std::size_t done = 0;
  const std::vector<WorkItemResult> results = workers.map(total, [&](std::size_t k) {
    const std::vector<double> point = pointAt(k);
    const std::string name = pointName(parameters, point);
    double value = 0.0;
    int steps = 0;
    try {
      const Scene at = parameters.withValues(
          scene, Eigen::Map<const Eigen::VectorXd>(point.data(), point.size()));
      const ForwardPass pass = runForwardPass(at);
      steps = pass.unconvergedSteps;
      value = loss.value(at, pass.trajectory);
    } catch (const InputError& e) {
      throw InputError(e.file(), e.path(), e.reason() + " (at grid point " + name + ")");
    } catch (const NumericalError& e) {
      throw NumericalError(e.step(), e.module(), e.quantity() + " (at grid point " + name + ")");
    }
    if (!std::isfinite(value))
      throw NumericalError(0, "landscape", "loss is not finite at grid point " + name);
    if (!quiet) std::fprintf(stderr, "\rpoint %zu/%zu, loss %.6e   ", ++done, total, value);
    std::string bytes(sizeof value + sizeof steps, '\0');
    std::memcpy(bytes.data(), &value, sizeof value);
    std::memcpy(bytes.data() + sizeof value, &steps, sizeof steps);
    return bytes;
  });
  for (std::size_t k = 0; k < total; ++k) {
    if (!results[k].ok) rethrowFailure(results[k]);  // the first failing point, as serially
    double value = 0.0;
    int steps = 0;
    std::memcpy(&value, results[k].data.data(), sizeof value);
    std::memcpy(&steps, results[k].data.data() + sizeof value, sizeof steps);
    unconverged += steps;
    const std::vector<double> point = pointAt(k);
    losses.push_back(value);
    if (value < best) best = value, bestPoint = point;
    for (double v : point) csv << v << ",";
    csv << value << "\n";
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!quiet) std::fprintf(stderr, "\n");
  if (!workers.isRoot()) return 0;
  {
    std::ofstream file(out->file("landscape.csv"));
    file << csv.str();
    file.close();
    if (!file) throw InputError(outDir, "landscape.csv", "cannot write");
  }

  std::string plotNote;
  const std::vector<double> scenePoint(sceneValues.data(), sceneValues.data() + sceneValues.size());
  if (!plotLandscape(out->file("landscape.png"), scene.name + ": task loss landscape", parameters,
                     axes, losses, scenePoint, plotNote))
    std::fprintf(stderr, "warning: %s\n", plotNote.c_str());
  out->commit();

  if (unconverged > 0)
    std::fprintf(stderr,
                 "warning: %d forward steps stopped above solver.pd_tolerance over the grid\n",
                 unconverged);
  std::printf(
      "landscape: %s: %zu points, %lld simulated steps, min loss %.6e at %s, %.2f s -> %s\n",
      scene.name.c_str(), total, static_cast<long long>(total) * scene.time.steps, best,
      pointName(parameters, bestPoint).c_str(), seconds, outDir.c_str());
  return 0;
}

}  // namespace weft::cli
