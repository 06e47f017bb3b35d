// `weft bench distribution`: two measurements on this launch and one projection.
//
// 1. Hand-out cost: a map of many empty items (rank 0's hand-out rate, the limit for tiny
//    items) and of items that each spin for a fixed time (the efficiency against the ideal
//    count x time / ranks).
// 2. The projection: the runs of a finished comparison (their wall seconds, in the order the
//    benchmark makes them) handed out to P ranks by list scheduling, plus the measured hand-out
//    cost per item and the comparison's serial part; the longest run bounds any P from below.

#include "DistributionBench.h"

#include "ApplicationTasks.h"
#include "BenchTable.h"

#include <weft/core/Error.h>
#include <weft/io/StagedDirectory.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <queue>
#include <sstream>
#include <tuple>

namespace weft::bench {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Busy for `seconds` (a sleep would let two ranks share one core and flatter the efficiency).
void spin(double seconds) {
  const auto start = Clock::now();
  volatile double sink = 0.0;
  while (secondsSince(start) < seconds) sink = sink + 1.0;
}

std::string format(double v, int digits = 4) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", digits, v);
  return text;
}

struct StoredRun {
  int task, seed, method;
  double seconds;
};

// The runs of a comparison's runs/ folder in the order readStoredRuns makes jobs: task table
// order, then seed, then method.
std::vector<StoredRun> readRunDurations(const std::string& store) {
  std::vector<StoredRun> runs;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(store, ec)) {
    if (entry.path().extension() != ".csv") continue;
    std::ifstream in(entry.path());
    std::string line, last;
    std::getline(in, line);  // header
    while (std::getline(in, line))
      if (!line.empty()) last = line;
    std::vector<std::string> cells;
    std::stringstream row(last);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    if (cells.size() < 7) throw InputError(entry.path().string(), "wall_s", "not a stored run");
    StoredRun r{-1, std::atoi(cells[2].c_str()), -1, std::atof(cells[5].c_str())};
    for (int t = 0; t < static_cast<int>(std::size(kApplicationTasks)); ++t)
      if (cells[0] == kApplicationTasks[t].name) r.task = t;
    for (int m = 0; m < kApplicationMethodCount; ++m)
      if (cells[1] == kApplicationMethods[m].name) r.method = m;
    if (r.task < 0 || r.method < 0)
      throw InputError(entry.path().string(), "task", "unknown task or method " + cells[0]);
    runs.push_back(r);
  }
  if (ec || runs.empty()) throw InputError(store, "--store", "holds no stored runs");
  std::sort(runs.begin(), runs.end(), [](const StoredRun& a, const StoredRun& b) {
    return std::tie(a.task, a.seed, a.method) < std::tie(b.task, b.seed, b.method);
  });
  return runs;
}

}  // namespace

double listScheduleSeconds(const std::vector<double>& durations, int ranks, double perItem) {
  std::priority_queue<double, std::vector<double>, std::greater<double>> free;
  for (int r = 0; r < ranks; ++r) free.push(0.0);
  double makespan = 0.0;
  for (double d : durations) {
    const double start = free.top();
    free.pop();
    const double end = start + d + perItem;
    makespan = std::max(makespan, end);
    free.push(end);
  }
  return makespan;
}

int runDistributionBench(const DistributionBenchOptions& options, const std::string& outDir) {
  const std::unique_ptr<WorkDistributor> serial =
      options.workers ? nullptr : makeSerialDistributor();
  WorkDistributor& workers = options.workers ? *options.workers : *serial;
  const int ranks = workers.size();

  // 1. Hand-out cost.
  const std::size_t tiny = options.quick ? 2000 : 20000;
  auto start = Clock::now();
  workers.map(tiny, [](std::size_t) { return std::string(); });
  const double tinySeconds = secondsSince(start);
  const double perItem = tinySeconds / static_cast<double>(tiny);
  struct Spin {
    double itemSeconds;
    std::size_t items;
    double wall = 0.0;
  };
  std::vector<Spin> spins = {{0.001, options.quick ? 200u : 2000u},
                             {0.01, options.quick ? 40u : 400u},
                             {0.1, options.quick ? 8u : 40u}};
  for (Spin& s : spins) {
    start = Clock::now();
    workers.map(s.items, [&](std::size_t) {
      spin(s.itemSeconds);
      return std::string();
    });
    s.wall = secondsSince(start);
  }
  if (!workers.isRoot()) return 0;

  StagedDirectory out(outDir);
  BenchTable handout(
      {"processes", "items", "item_s", "wall_s", "ideal_s", "efficiency", "handout_us_per_item"});
  handout.add({workers.description(), std::to_string(tiny), "0", format(tinySeconds), "0", "-",
               format(1e6 * perItem, 3)});
  for (const Spin& s : spins) {
    const double ideal = s.itemSeconds * static_cast<double>(s.items) / ranks;
    handout.add({workers.description(), std::to_string(s.items), format(s.itemSeconds),
                 format(s.wall), format(ideal), format(ideal / s.wall, 3),
                 format(1e6 * (s.wall - ideal) * ranks / static_cast<double>(s.items), 3)});
  }

  // The time a rank loses per item it is handed, from the shortest spinning items: a rank other
  // than 0 asks rank 0 by message and waits for its answer (rank 0's own items cost no message,
  // which is why the empty items above run at rank 0's local rate).
  const Spin& shortest = spins.front();
  const double lostPerItem = std::max(
      0.0, (shortest.wall - shortest.itemSeconds * static_cast<double>(shortest.items) / ranks) *
               ranks / static_cast<double>(shortest.items));

  // 2. Projection.
  std::string store = options.store;
  if (store.empty())
    store = fs::exists("docs/runs/full") ? "docs/runs/full"
                                         : std::string(WEFT_SOURCE_DIR) + "/docs/runs/full";
  const std::vector<StoredRun> runs = readRunDurations(store);
  std::vector<double> durations;
  double total = 0.0, longest = 0.0;
  for (const StoredRun& r : runs) {
    durations.push_back(r.seconds);
    total += r.seconds;
    longest = std::max(longest, r.seconds);
  }
  const double serialOne = options.serialSeconds + listScheduleSeconds(durations, 1, lostPerItem);
  BenchTable projection(
      {"ranks", "projected_wall_s", "projected_wall_h", "speedup", "efficiency", "bound"});
  for (int p : options.ranks) {
    const double wall = options.serialSeconds + listScheduleSeconds(durations, p, lostPerItem);
    const bool runBound = wall < options.serialSeconds + longest * 1.05;
    projection.add({std::to_string(p), format(wall), format(wall / 3600.0, 3),
                    format(serialOne / wall, 3), format(serialOne / wall / p, 3),
                    runBound ? "longest run" : "runs"});
  }
  handout.writeCsv(out.file("distribution.csv"));
  projection.writeCsv(out.file("projection.csv"));
  std::ofstream md(out.file("distribution.md"));
  handout.writeMarkdown(
      md, "Handing out work items",
      "Machine: " + machineDescription() + "; " + workers.description() +
          ". A map() of empty items: rank 0 takes items without a message, so with nothing to "
          "do it runs nearly all of them itself and this row is the floor of the bookkeeping, "
          "not the cost of a message. Items that each keep a core busy for item_s measure the "
          "efficiency against the ideal items x item_s / processes; handout_us_per_item is the "
          "time lost per item (a request to rank 0 and its answer, each wait polling with sleeps "
          "of up to 1 ms so that a waiting rank leaves its core to the others, and the end of "
          "the map, when some ranks have no item left).");
  md << "\n";
  projection.writeMarkdown(
      md, "The comparison on P ranks, projected",
      "From " + std::to_string(runs.size()) + " stored runs (" + store + ": " + format(total) +
          " s of runs, the longest " + format(longest) +
          " s) handed out in the benchmark's order to the first free rank, plus " +
          format(1e6 * lostPerItem, 3) +
          " us lost per run (the 1 ms items' handout_us_per_item above) and " +
          format(options.serialSeconds) +
          " s that no rank shares (set-up, timed passes, tables: --serial-seconds). The runs' "
          "wall seconds were measured two at a time on this machine's two cores. 'longest run': "
          "the wall time is the longest single run's, and more ranks cannot lower it.");
  md.close();
  out.commit();
  std::printf(
      "bench distribution: %s, %.3g us lost per 1 ms item; comparison on 8 ranks "
      "projected %.3g h (longest run %.3g h) -> %s/distribution.md\n",
      workers.description().c_str(), 1e6 * lostPerItem,
      (options.serialSeconds + listScheduleSeconds(durations, 8, lostPerItem)) / 3600.0,
      longest / 3600.0, outDir.c_str());
  return 0;
}

}  // namespace weft::bench
