// `weft bench NAME [options]`: the command line of the benchmarks (bench/weft/bench/, one entry
// point each): parses and checks the options, then runs the benchmark named.

#include "BuildInfo.h"
#include "CommandLine.h"
#include "Commands.h"

#include <weft/bench/ApplicationsBench.h>
#include <weft/bench/BackwardBench.h>
#include <weft/bench/BenchAssets.h>
#include <weft/bench/BenchNames.h>
#include <weft/bench/ContactBench.h>
#include <weft/bench/ContinuityBench.h>
#include <weft/bench/DistributionBench.h>
#include <weft/bench/ForwardBench.h>
#include <weft/bench/ImpactZonesBench.h>
#include <weft/bench/PaperMeshScenes.h>
#include <weft/bench/SoakBench.h>
#include <weft/core/Error.h>
#include <weft/distributed/WorkDistributor.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>

namespace weft::cli {
namespace {

using bench::ApplicationTask;
using bench::kApplicationMethodCount;
using bench::kApplicationMethods;
using bench::kApplicationTasks;
using bench::kQuickApplicationTask;
namespace fs = std::filesystem;

// A comma-separated list of names given to `option` (or `fallback`), each one of `known`; an
// unknown name fails naming the option.
std::vector<std::string> benchNames(const CommandLine& cl, const std::string& option,
                                    const std::string& fallback,
                                    const std::vector<std::string>& known) {
  const std::string text = cl.value(option, fallback);
  std::vector<std::string> out;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t comma = std::min(text.find(',', begin), text.size());
    out.push_back(text.substr(begin, comma - begin));
    if (std::find(known.begin(), known.end(), out.back()) == known.end()) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      cl.fail(option, "unknown name '" + out.back() + "' (known: " + list + ")");
    }
    begin = comma + 1;
  }
  return out;
}

// --resolutions: a comma-separated list of quads per side (e.g. 12,24); empty when the option is
// absent (the benchmark's own list).
std::vector<int> benchResolutions(const CommandLine& cl) {
  if (!cl.has("--resolutions")) return {};
  std::vector<int> out;
  const std::string text = cl.value("--resolutions", "");
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t comma = std::min(text.find(',', begin), text.size());
    const std::string item = text.substr(begin, comma - begin);
    char* end = nullptr;
    const long n = std::strtol(item.c_str(), &end, 10);
    if (item.empty() || *end != '\0' || n < 1 || n > 1024)
      cl.fail(
          "--resolutions",
          "expects quads per side as a comma-separated list, e.g. 12,24,48; got '" + text + "'");
    out.push_back(static_cast<int>(n));
    begin = comma + 1;
  }
  return out;
}

std::vector<const ApplicationTask*> selectTasks(const CommandLine& cl, bool quick) {
  std::string known;
  for (const ApplicationTask& t : kApplicationTasks)
    known += (known.empty() ? "" : ", ") + std::string(t.name);
  const std::string list = cl.value("--tasks", quick ? kQuickApplicationTask : "");
  std::vector<const ApplicationTask*> out;
  if (list.empty()) {
    for (const ApplicationTask& t : kApplicationTasks) out.push_back(&t);
    return out;
  }
  std::stringstream items(list);
  for (std::string name; std::getline(items, name, ',');) {
    const ApplicationTask* found = nullptr;
    for (const ApplicationTask& t : kApplicationTasks)
      if (name == t.name) found = &t;
    if (!found) cl.fail("--tasks", "unknown task '" + name + "' (known: " + known + ")");
    if (std::find(out.begin(), out.end(), found) == out.end()) out.push_back(found);
  }
  if (out.empty())
    cl.fail("--tasks", "expects a comma-separated list of tasks (known: " + known + ")");
  return out;
}

// --seeds N[,task=M,...]: N seeds per task, M for the tasks named (the Sock's runs take hours
// each, so one command can run it with fewer seeds than the rest). Returns the count per task of
// `tasks`, in their order.
std::vector<int> selectSeeds(const CommandLine& cl, bool quick,
                             const std::vector<const ApplicationTask*>& tasks) {
  const std::string text = cl.value("--seeds", quick ? "1" : "3");
  const auto count = [&](const std::string& item) {
    char* end = nullptr;
    const long n = std::strtol(item.c_str(), &end, 10);
    if (item.empty() || *end || n < 1 || n > 100)
      cl.fail("--seeds", "expects N or N,task=M,... with whole numbers 1..100, got '" + item + "'");
    return static_cast<int>(n);
  };
  std::stringstream items(text);
  std::string item;
  std::getline(items, item, ',');
  std::vector<int> seeds(tasks.size(), count(item));
  while (std::getline(items, item, ',')) {
    const std::size_t eq = item.find('=');
    if (eq == std::string::npos)
      cl.fail("--seeds", "expects N or N,task=M,...: '" + item + "' is not task=M");
    const std::string name = item.substr(0, eq);
    bool found = false;
    for (std::size_t t = 0; t < tasks.size(); ++t)
      if (name == tasks[t]->name) seeds[t] = count(item.substr(eq + 1)), found = true;
    if (!found) cl.fail("--seeds", "names '" + name + "', which is not one of the tasks run");
  }
  return seeds;
}

// --methods: which methods make runs (all by default).
std::array<bool, bench::kApplicationMethodCount> selectMethods(const CommandLine& cl) {
  std::array<bool, bench::kApplicationMethodCount> selected;
  std::string known;
  for (const bench::ApplicationMethod& m : kApplicationMethods)
    known += (known.empty() ? "" : ", ") + std::string(m.name);
  const std::string list = cl.value("--methods", "");
  selected.fill(list.empty());
  std::stringstream items(list);
  for (std::string name; std::getline(items, name, ',');) {
    int found = -1;
    for (int m = 0; m < kApplicationMethodCount; ++m)
      if (name == kApplicationMethods[m].name) found = m;
    if (found < 0) cl.fail("--methods", "unknown method '" + name + "' (known: " + known + ")");
    selected[found] = true;
  }
  if (std::find(selected.begin(), selected.end(), true) == selected.end())
    cl.fail("--methods", "expects a comma-separated list of methods (known: " + known + ")");
  return selected;
}

bench::ApplicationsBenchOptions applicationsOptions(const CommandLine& cl) {
  bench::ApplicationsBenchOptions o;
  o.quick = cl.has("--quick");
  o.resume = cl.has("--resume");
  o.tasks = selectTasks(cl, o.quick);
  o.methods = selectMethods(cl);
  o.seeds = selectSeeds(cl, o.quick, o.tasks);
  o.threads = cl.integer("--threads", 1, 1, 1024);
  o.jobs = cl.integer("--jobs", 1, 1, 64);
  const double budgetOption = cl.number("--budget", 0.0);
  if (cl.has("--budget") &&
      !(budgetOption >= 1.0 && budgetOption <= 1e15 && std::floor(budgetOption) == budgetOption))
    cl.fail("--budget", "must be a positive whole number of simulated steps");
  o.budget = cl.has("--budget") ? static_cast<long long>(budgetOption) : 0;
  OptimizerSettings& lbfgsb = o.lbfgsb;
  lbfgsb.lbfgsbFirstStep = cl.number("--first-step", lbfgsb.lbfgsbFirstStep);
  if (!(lbfgsb.lbfgsbFirstStep > 0.0 && std::isfinite(lbfgsb.lbfgsbFirstStep)))
    cl.fail("--first-step", "must be a finite length > 0 (optimiser coordinates)");
  lbfgsb.lbfgsbMinCurvatureStep = cl.number("--min-curvature-step", lbfgsb.lbfgsbMinCurvatureStep);
  if (!(lbfgsb.lbfgsbMinCurvatureStep >= 0.0 && std::isfinite(lbfgsb.lbfgsbMinCurvatureStep)))
    cl.fail("--min-curvature-step", "must be a finite length >= 0 (optimiser coordinates)");
  // --paper-meshes [DIR]: benchCommand hands a bare --paper-meshes over as an empty value.
  if (cl.has("--paper-meshes")) {
    std::string paperDir = cl.value("--paper-meshes", "");
    if (paperDir.empty()) {
      fs::path repository = fs::path(bench::assetFile("scenes")).parent_path().parent_path();
      paperDir =
          bench::paper::defaultPaperMeshDirectory(repository.empty() ? "." : repository.string());
    }
    const std::string missing = bench::paper::missingPaperMeshes(paperDir);
    if (!missing.empty()) throw InputError(paperDir, "--paper-meshes", missing);
    o.paperMeshes = fs::absolute(paperDir).lexically_normal().string();
  }
  o.build = buildInfoJson();
  return o;
}

}  // namespace

int benchCommand(const std::vector<std::string>& arguments) {
  // The render benchmark has its own options (--frames, --size, --backend).
  if (!arguments.empty() && arguments[0] == "render")
    return renderBenchmark({arguments.begin() + 1, arguments.end()});
  // --paper-meshes takes an optional folder: the next argument, unless it is an option or a
  // benchmark name; bare, it is handed on with an empty value (the default folder).
  std::vector<std::string> args;
  for (std::size_t i = 0; i < arguments.size(); ++i) {
    if (arguments[i] != "--paper-meshes") {
      args.push_back(arguments[i]);
      continue;
    }
    const bool hasValue = i + 1 < arguments.size() && arguments[i + 1].rfind("-", 0) != 0 &&
                          arguments[i + 1] != "applications";
    args.push_back("--paper-meshes=" + (hasValue ? arguments[++i] : std::string()));
  }
  CommandLine cl(args, {"--out",          "--scene",       "--scenes",     "--threads",
                        "--resolutions",  "--tasks",       "--methods",    "--seeds",
                        "--budget",       "--jobs",        "--contact",    "--paper-meshes",
                        "--subdivisions", "--resolution",  "--first-step", "--min-curvature-step",
                        "--steps",        "--evaluations", "--store",      "--serial-seconds"},
                 {"--quick", "--resume", "--calibrate"});
  if (cl.positional().size() != 1)
    cl.fail("NAME", "bench takes one benchmark name (" + bench::benchNameList() + ")");
  const std::string name = cl.positional()[0];
  const std::string out = cl.value("--out", "out/bench-" + name);
  for (const char* option : {"--subdivisions", "--resolution"})
    if (cl.has(option) && name != "continuity")
      cl.fail(option, "applies to the continuity benchmark only");
  if (cl.has("--steps") && name != "soak" && name != "impact_zones")
    cl.fail("--steps", "applies to the soak and impact_zones benchmarks only");
  if (cl.has("--evaluations") && name != "soak")
    cl.fail("--evaluations", "applies to the soak benchmark only");
  if (cl.has("--calibrate") && name != "backward")
    cl.fail("--calibrate", "applies to the backward benchmark only");
  if (name == "applications") {
    if (cl.has("--resolutions"))
      cl.fail("--resolutions",
              "applies to the forward, backward, contact and impact_zones benchmarks only");
    if (cl.has("--contact")) cl.fail("--contact", "applies to the contact benchmark only");
    bench::ApplicationsBenchOptions options = applicationsOptions(cl);
    if (launchSize() > 1 && options.jobs > 1)
      cl.fail("--jobs", "under mpirun each rank makes one run at a time: use more ranks");
    options.workers = &processWorkers();
    return bench::runApplicationsBench(options, out);
  }
  for (const char* option : {"--store", "--serial-seconds"})
    if (cl.has(option) && name != "distribution")
      cl.fail(option, "applies to the distribution benchmark only");
  if (name == "distribution") {
    bench::DistributionBenchOptions o;
    o.quick = cl.has("--quick");
    o.store = cl.value("--store", "");
    o.serialSeconds = cl.number("--serial-seconds", o.serialSeconds);
    if (!(o.serialSeconds >= 0.0 && o.serialSeconds < 1e9))
      cl.fail("--serial-seconds", "must be a number of seconds >= 0");
    o.workers = &processWorkers();
    return bench::runDistributionBench(o, out);
  }
  // The other benchmarks time one process: under mpirun, rank 0 runs them alone.
  if (launchRank() != 0) throw QuietExit{0};
  for (const char* option : {"--tasks", "--methods", "--seeds", "--budget", "--jobs", "--resume",
                             "--paper-meshes", "--first-step", "--min-curvature-step"})
    if (cl.has(option)) cl.fail(option, "applies to the applications benchmark only");
  const bool quick = cl.has("--quick");
  const int threads = cl.integer("--threads", 1, 1, 1024);
  if (name == "contact") {
    bench::ContactBenchOptions o;
    o.quick = quick;
    o.threads = threads;
    if (cl.has("--scenes")) o.scenes = benchNames(cl, "--scenes", "", bench::kContactBenchScenes);
    o.resolutions = benchResolutions(cl);
    if (cl.has("--contact")) o.contacts = benchNames(cl, "--contact", "", bench::kContactSolves);
    return bench::runContactBench(o, out);
  }
  if (name == "impact_zones") {
    if (cl.has("--contact")) cl.fail("--contact", "bench impact_zones runs its scene's own");
    for (const char* option : {"--scene", "--scenes"})
      if (cl.has(option)) cl.fail(option, "bench impact_zones runs its own scene (crumple)");
    bench::ImpactZonesBenchOptions o;
    o.quick = quick;
    o.threads = threads;
    o.resolutions = benchResolutions(cl);
    o.steps = cl.integer("--steps", 0, 1, 100000);
    return bench::runImpactZonesBench(o, out);
  }
  if (cl.has("--contact") && name != "continuity")
    cl.fail("--contact", "applies to the contact and continuity benchmarks only");
  if (name == "soak") {
    if (cl.has("--resolutions"))
      cl.fail("--resolutions",
              "applies to the forward, backward, contact and impact_zones benchmarks only");
    for (const char* option : {"--scene", "--scenes"})
      if (cl.has(option)) cl.fail(option, "bench soak runs its own two scenes");
    bench::SoakBenchOptions o;
    o.quick = quick;
    o.threads = threads;
    o.steps = cl.integer("--steps", 0, 1, 100000000);
    o.evaluations = cl.integer("--evaluations", 0, 1, 1000000);
    return bench::runSoakBench(o, out);
  }
  if (name == "forward") {
    bench::ForwardBenchOptions o;
    o.quick = quick;
    o.scene = cl.value("--scene", "");
    o.threads = threads;
    o.resolutions = benchResolutions(cl);
    return bench::runForwardBench(o, out);
  }
  if (name == "backward") {
    bench::BackwardBenchOptions o;
    o.quick = quick;
    if (cl.has("--scenes")) o.scenes = benchNames(cl, "--scenes", "", bench::kBackwardBenchScenes);
    o.threads = threads;
    o.resolutions = benchResolutions(cl);
    o.calibrate = cl.has("--calibrate");
    return bench::runBackwardBench(o, out);
  }
  if (cl.has("--resolutions"))
    cl.fail("--resolutions",
            "applies to the forward, backward, contact and impact_zones benchmarks only");
  if (name == "continuity") {
    bench::ContinuityBenchOptions o;
    o.quick = quick;
    o.scene = cl.value("--scene", "");
    o.threads = threads;
    const std::vector<std::string> contacts =
        benchNames(cl, "--contact", "newton", bench::kContactSolves);
    if (contacts.size() != 1) cl.fail("--contact", "bench continuity takes one contact solve");
    o.contact = contacts.front();
    o.subdivisions = cl.integer("--subdivisions", 2, 0, 5);
    o.resolution = cl.integer("--resolution", 0, 0, 400);
    return bench::runContinuityBench(o, out);
  }
  cl.fail("NAME", "unknown benchmark '" + name + "' (known: " + bench::benchNameList() + ")");
}

}  // namespace weft::cli
