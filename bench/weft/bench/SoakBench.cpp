// `weft bench soak`: does a long run leak or slow down?
//
// Contact: the Sphere scene's cloth, centred over the sphere so that it drapes and stays there
// (contact with the sphere and self-collision every step), stepped `steps` times without a
// recorded trajectory. Optimiser: Adam on the wind_sysid task (forward pass and adjoint at every
// evaluation) for `evaluations` evaluations. Each is cut into 100 windows (or one per step or
// evaluation when there are fewer); each window records the mean wall time per step or per
// evaluation and the resident memory (VmRSS) at its end.
//
// After a warm-up of the first 10 % (first factorisations, buffers growing to their working
// size), memory must not grow and time must not drift: the last window's resident memory is
// compared with the warm-up's end, and the mean time of the last tenth of the windows with the
// first tenth after the warm-up.

#include "SoakBench.h"

#include "BenchAssets.h"
#include "BenchTable.h"
#include "ProcessMemory.h"

#include <weft/io/StagedDirectory.h>
#include <weft/optim/OptimizationRun.h>
#include <weft/physics/Simulator.h>
#include <weft/scene/SceneLoader.h>

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <string>
#include <vector>

namespace weft::bench {
namespace {

struct Soak {
  std::string phase, unit;
  long long count = 0;
  std::vector<SoakWindow> windows;
  int unconverged = 0;  // contact: steps that ended at their iteration cap
};

Soak soakContact(int steps) {
  Soak s;
  s.phase = "contact";
  s.unit = "step";
  // The Sphere scene's cloth centred over the sphere: it drapes symmetrically and stays.
  const Scene scene = loadScene(
      assetFile("scenes/sphere.json"),
      {{"cloths.0.mesh.transform.translate", "[0,0.4,0]"}, {"time.steps", std::to_string(steps)}});
  Simulator sim(scene);
  const int perWindow = std::max(1, steps / 100);
  for (int done = 0; done < steps;) {
    const int n = std::min(perWindow, steps - done);
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < n; ++i) s.unconverged += !sim.step().converged;
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    done += n;
    s.windows.push_back({done, ms / n, residentMemoryMb()});
  }
  s.count = steps;
  return s;
}

Soak soakOptimiser(int evaluations) {
  Soak s;
  s.phase = "optimiser";
  s.unit = "evaluation";
  const Scene scene = loadScene(assetFile("scenes/wind_sysid.json"));
  OptimizationRun run(scene, "adam");
  OptimizerSettings settings;
  settings.maxEvaluations = evaluations;
  settings.gradientTolerance = 0.0;  // run the whole budget
  settings.lossTolerance = 0.0;
  const int perWindow = std::max(1, evaluations / 100);
  int inWindow = 0;
  auto start = std::chrono::steady_clock::now();
  OptimizationCallbacks callbacks;
  callbacks.evaluated = [&](const LogEntry& entry, const Eigen::VectorXd&) {
    if (++inWindow < perWindow) return;
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    s.windows.push_back({entry.evaluation, ms / inWindow, residentMemoryMb()});
    inWindow = 0;
    start = std::chrono::steady_clock::now();
  };
  const OptimizationOutcome outcome = run.run(settings, callbacks);
  s.count = outcome.result.evaluations;
  return s;
}

double meanMs(const std::vector<SoakWindow>& w, std::size_t from, std::size_t to) {
  if (to <= from) return 0.0;
  double sum = 0.0;
  for (std::size_t i = from; i < to; ++i) sum += w[i].msPerUnit;
  return sum / double(to - from);
}

}  // namespace

SoakJudgement judgeSoak(const std::vector<SoakWindow>& windows) {
  SoakJudgement j;
  const std::size_t n = windows.size();
  if (n == 0) return j;
  const std::size_t warm = std::min(n, std::max<std::size_t>(1, n / 10));
  const std::size_t tenth = std::max<std::size_t>(1, (n - warm) / 10);
  j.warmupRssMb = windows[warm - 1].rssMb;
  j.endRssMb = windows.back().rssMb;
  j.growthMb = j.endRssMb - j.warmupRssMb;
  if (warm < n) {
    j.firstMs = meanMs(windows, warm, std::min(warm + tenth, n));
    j.lastMs = meanMs(windows, n - std::min(tenth, n - warm), n);
    j.drift = j.firstMs > 0.0 ? j.lastMs / j.firstMs : 1.0;
  }
  j.memoryGrew = j.growthMb > kSoakMemoryGrowthLimitMb;
  j.timeDrifted = j.drift > kSoakTimeDriftLimit;
  return j;
}

int runSoakBench(const SoakBenchOptions& options, const std::string& outDir) {
  omp_set_num_threads(options.threads);
  StagedDirectory out(outDir);
  const int steps = options.steps > 0 ? options.steps : options.quick ? 100 : 100000;
  const int evaluations = options.evaluations > 0 ? options.evaluations : options.quick ? 20 : 500;
  const auto start = std::chrono::steady_clock::now();
  std::vector<Soak> soaks;
  std::fprintf(stderr, "soak: contact, %d steps\n", steps);
  soaks.push_back(soakContact(steps));
  std::fprintf(stderr, "soak: optimiser, %d evaluations\n", evaluations);
  soaks.push_back(soakOptimiser(evaluations));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  BenchTable samples({"phase", "done", "ms_per_unit", "rss_mb"});
  BenchTable summary({"phase", "count", "unit", "unconverged_steps", "rss_after_warmup_mb",
                      "rss_end_mb", "growth_mb", "ms_first_tenth", "ms_last_tenth", "drift",
                      "verdict"});
  std::vector<PlotSeries> rss;
  bool ok = true;
  std::vector<SoakJudgement> judgements;
  for (const Soak& s : soaks) {
    const SoakJudgement j = judgeSoak(s.windows);
    judgements.push_back(j);
    PlotSeries series;
    series.title = s.phase + " (per " + s.unit + ")";
    for (const SoakWindow& w : s.windows) {
      samples.add(
          {s.phase, std::to_string(w.end), formatNumber(w.msPerUnit, 5), formatNumber(w.rssMb, 5)});
      series.x.push_back(100.0 * double(w.end) / double(std::max<long long>(1, s.count)));
      series.y.push_back(w.rssMb);
    }
    rss.push_back(series);
    const std::string verdict = j.memoryGrew    ? "memory grew"
                                : j.timeDrifted ? "time drifted"
                                                : "steady";
    ok = ok && !j.memoryGrew && !j.timeDrifted;
    summary.add({s.phase, std::to_string(s.count), s.unit,
                 s.phase == "contact" ? std::to_string(s.unconverged) : "-",
                 formatNumber(j.warmupRssMb), formatNumber(j.endRssMb), formatNumber(j.growthMb, 3),
                 formatNumber(j.firstMs), formatNumber(j.lastMs), formatNumber(j.drift, 3),
                 verdict});
  }
  samples.writeCsv(out.file("soak.csv"));
  const std::string preamble =
      "contact: assets/scenes/sphere.json with its cloth centred over the sphere "
      "(cloths.0.mesh.transform.translate [0,0.4,0]), " +
      std::to_string(steps) +
      " steps without a recorded trajectory. optimiser: Adam on assets/scenes/wind_sysid.json, " +
      std::to_string(evaluations) +
      " evaluations (forward pass and adjoint each). Each run is sampled in up to 100 windows "
      "(soak.csv: mean wall ms per step or evaluation, VmRSS at the window's end). After a "
      "warm-up of the first tenth of the windows: growth_mb is the last window's resident memory "
      "minus the warm-up's last (limit " +
      formatNumber(kSoakMemoryGrowthLimitMb) +
      " MB), drift the mean time of the last tenth of the windows over the first tenth after "
      "the warm-up (limit " +
      formatNumber(kSoakTimeDriftLimit) + "). " + std::to_string(options.threads) + " thread(s), " +
      formatNumber(seconds, 4) + " s in all. Machine: " + machineDescription() + ".";
  summary.writeCsv(out.file("soak_summary.csv"));
  summary.writeMarkdown(out.file("soak.md"), "Long runs (weft bench soak)", preamble);
  std::string reason;
  if (!plotSeries(out.file("soak.png"), "Resident memory through the soak runs",
                  "percent of the run", "VmRSS (MB)", rss, false, false, reason))
    std::fprintf(stderr, "warning: %s\n", reason.c_str());
  out.commit();
  for (std::size_t i = 0; i < soaks.size(); ++i)
    std::printf("bench soak: %s: %lld %ss, memory %+.1f MB after warm-up, time x%.3f%s\n",
                soaks[i].phase.c_str(), soaks[i].count, soaks[i].unit.c_str(),
                judgements[i].growthMb, judgements[i].drift,
                judgements[i].memoryGrew || judgements[i].timeDrifted ? " (beyond a limit)" : "");
  std::printf("bench soak: %.1f s -> %s/soak.{csv,md,png}\n", seconds, outDir.c_str());
  return ok ? 0 : 1;
}

}  // namespace weft::bench
