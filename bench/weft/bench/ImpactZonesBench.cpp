// `weft bench impact_zones`: Liang et al. 2019 Table 1, the ablation of their QR backward pass
// through the impact-zone QP (Sec. 3.4.1-3.4.2) against the full KKT system (Eq. 13, OptNet's).
//
// Scene: assets/scenes/crumple.json (their Sec. 4.1 / Fig. 2: a cloth dropped into an
// upside-down square pyramid, a `mesh` obstacle) with the cloth's self-collision switched to
// the impact-zone model, at n x n quads. The simulator runs forward; an observer on its
// impact-zone response (ImpactZoneResponse::setObserver) sees every accepted step's final zones,
// and each zone's QP (the dense form of a large zone's sparse one) is differentiated at once by
// zoneQpGradientKkt and zoneQpGradientQr with the same dL/dz (normal entries from a fixed seed),
// each call repeated until the repetitions take kMinSeconds so that small zones are above the
// timer's resolution. Zones whose KKT matrix is singular are counted, not dropped (their LU's
// time counts like any other); where both routes give a gradient they are compared.
//
// Matrix size: n + m for the KKT route (n = 3 x the zone's free nodes, m its impact rows, the
// paper's "baseline"), the numerical rank of the rows with lambda > 0 for the QR route (the
// size of R_1, the paper's "ours").

#include "ImpactZonesBench.h"

#include "BenchAssets.h"
#include "BenchTable.h"

#include <weft/collision/ImpactZoneResponse.h>
#include <weft/collision/ImpactZones.h>
#include <weft/collision/MeshCrossingCheck.h>
#include <weft/collision/SparseZoneQp.h>
#include <weft/collision/ZoneQp.h>
#include <weft/core/Error.h>
#include <weft/io/StagedDirectory.h>
#include <weft/physics/Simulator.h>
#include <weft/scene/SceneLoader.h>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

namespace weft::bench {
namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Seconds per call of f, repeated until the calls take minSeconds (at least one call).
template <class F>
double secondsPerCall(F&& f, double minSeconds) {
  const auto start = Clock::now();
  int calls = 0;
  double elapsed = 0.0;
  do {
    f();
    ++calls;
    elapsed = since(start);
  } while (elapsed < minSeconds);
  return elapsed / calls;
}

double maxAbs(const Eigen::MatrixXd& a) {
  return a.size() ? a.cwiseAbs().maxCoeff() : 0.0;
}

// Both backward routes on one zone QP with the same dL/dz.
ZoneBackwardSample timeZoneBackward(const collision::ZoneQp& qp,
                                    const collision::ZoneQpSolution& solution,
                                    const Eigen::VectorXd& dLdz, double minSeconds) {
  ZoneBackwardSample s;
  s.n = static_cast<int>(qp.x.size());
  s.m = static_cast<int>(qp.h.size());
  collision::ZoneQpGradient kkt, qr;
  s.kktSeconds =
      secondsPerCall([&] { kkt = collision::zoneQpGradientKkt(qp, solution, dLdz); }, minSeconds);
  s.qrSeconds =
      secondsPerCall([&] { qr = collision::zoneQpGradientQr(qp, solution, dLdz); }, minSeconds);
  const Eigen::VectorXd g = qp.G * solution.z + qp.h;
  const Eigen::VectorXd scale = qp.h.cwiseAbs() + qp.G.cwiseAbs() * solution.z.cwiseAbs();
  for (Eigen::Index j = 0; j < g.size(); ++j)
    s.tightWithoutMultiplier += solution.lambda[j] == 0.0 && std::abs(g[j]) <= 1e-9 * scale[j];
  s.active = qr.activeConstraints;
  s.rank = qr.rank;
  s.kktOk = kkt.ok && qr.ok;
  if (s.kktOk) {
    const double scaleDx = std::max(maxAbs(kkt.dLdx), 1e-300);
    const double scaleAll = std::max({scaleDx, maxAbs(kkt.dLdG), maxAbs(kkt.dLdh)});
    s.differenceDx = maxAbs(qr.dLdx - kkt.dLdx) / scaleDx;
    s.differenceAll = std::max({maxAbs(qr.dLdx - kkt.dLdx), maxAbs(qr.dLdG - kkt.dLdG),
                                maxAbs(qr.dLdh - kkt.dLdh)}) /
                      scaleAll;
  }
  return s;
}

// The benchmark's scene at n x n quads: Crumple with impact-zone self-collision.
constexpr const char* kScene = "scenes/crumple.json";
// The collision thickness (m). Liang et al. give none; ARCSim's default is 1 mm, stacked.json
// uses 2 mm.
constexpr double kThickness = 0.002;
// Steps: the cloth reaches the pyramid's walls at about step 55 (h = 5 ms) and folds from then
// on; by step 120 each resolution has given hundreds of zone QPs (64^2 over two thousand), and
// 64^2's forward response then costs seconds per step, so the default run stops there.
constexpr int kSteps = 120;
constexpr int kQuickSteps = 100;
constexpr double kMinSeconds = 2e-3;
constexpr double kQuickMinSeconds = 2e-4;
constexpr unsigned kSeed = 20190338;  // dL/dz; fixed so that reruns time the same vectors

struct ResolutionRun {
  int quads = 0, vertices = 0, steps = 0, failedStep = 0;
  double forwardSeconds = 0.0;   // the run's wall time without the observer's timings
  double responseSeconds = 0.0;  // the impact_zones module's (forward response), observer excluded
  int unresolvedSteps = 0, splitSteps = 0, statesWithCrossings = 0, sparseZones = 0;
  int rigidZones = 0;  // moved by the failsafe's translation: no QP to differentiate
  double maxMove = 0.0;
  std::vector<ZoneBackwardSample> samples;
  std::vector<int> sampleStep;  // the step each sample's zone came from
};

// Crumple's document with the cloth's self-collision switched to impact zones (an object, which
// a scene override cannot set).
nlohmann::json benchScene() {
  const std::string file = assetFile(kScene);
  std::ifstream in(file);
  if (!in) throw InputError(file, "scene", "cannot be read");
  nlohmann::json doc = nlohmann::json::parse(in);
  doc["cloths"][0]["self_collision"] = {{"model", "impact_zones"}, {"thickness", kThickness}};
  return doc;
}

ResolutionRun runResolution(int quads, int steps, double minSeconds) {
  const std::string grid = "[" + std::to_string(quads) + "," + std::to_string(quads) + "]";
  const std::vector<SceneOverride> overrides = {{"cloths.0.mesh.grid.resolution", grid},
                                                {"time.steps", std::to_string(steps)}};
  const std::string file = assetFile(kScene);
  const Scene scene = loadSceneDocument(
      benchScene(), file, std::filesystem::path(file).parent_path().string(), overrides);
  ResolutionRun r;
  r.quads = quads;
  r.vertices = scene.vertexCount();
  Simulator sim(scene);
  collision::ImpactZoneResponse* response = sim.impactZoneResponse();
  if (!response) throw InputError(kScene, "cloths.0.self_collision", "no impact-zone response");
  // The independent edge-triangle check weft simulate's `crossings` column uses.
  const collision::MeshCrossingCheck crossings(
      collision::CollisionMesh::of(scene, sim.cloth(), false));
  std::mt19937 rng(kSeed);
  std::normal_distribution<double> normal;
  double observerSeconds = 0.0, observerInResponse = 0.0;
  int currentStep = 0;
  response->setObserver([&](const collision::ImpactZoneResult& result) {
    const auto start = Clock::now();
    for (const collision::ImpactZoneRecord& zone : result.zones) {
      if (zone.rigid) {
        ++r.rigidZones;
        continue;
      }
      const collision::ZoneQp dense = zone.sparse ? collision::toDense(zone.sparseQp) : zone.qp;
      r.sparseZones += zone.sparse;
      Eigen::VectorXd dLdz(dense.x.size());
      for (Eigen::Index i = 0; i < dLdz.size(); ++i) dLdz[i] = normal(rng);
      r.samples.push_back(timeZoneBackward(dense, zone.solution, dLdz, minSeconds));
      r.sampleStep.push_back(currentStep);
    }
    const double s = since(start);
    observerSeconds += s;
    observerInResponse += s;
  });
  const std::vector<std::string>& names = sim.moduleNames();
  const auto start = Clock::now();
  try {
    for (int s = 0; s < steps; ++s) {
      currentStep = s + 1;
      const StepStats& st = sim.step();
      r.unresolvedSteps += !st.impactsResolved;
      r.splitSteps += st.substeps > 1;
      r.maxMove = std::max(r.maxMove, st.impactMove);
      r.statesWithCrossings += crossings.count(sim.positions()) > 0;
      ++r.steps;
      if (r.steps % 20 == 0)
        std::fprintf(stderr, "impact_zones: %dx%d step %d, %zu zone QPs, %.0f s\n", quads, quads,
                     r.steps, r.samples.size(), since(start));
    }
  } catch (const NumericalError& e) {
    r.failedStep = r.steps + 1;
    std::fprintf(stderr, "\nimpact_zones: numerical failure: %s\n", e.what());
  }
  r.forwardSeconds = since(start) - observerSeconds;
  for (std::size_t m = 0; m < names.size(); ++m)
    if (names[m] == "impact_zones") r.responseSeconds = sim.moduleSeconds()[m] - observerInResponse;
  response->setObserver(nullptr);
  return r;
}

std::string meanSdText(const MeanSd& v, int precision) {
  return formatNumber(v.mean, precision) + " ± " + formatNumber(v.sd, 2);
}

}  // namespace

MeanSd meanSd(const std::vector<double>& values) {
  MeanSd out;
  if (values.empty()) return out;
  double sum = 0.0;
  for (double v : values) sum += v;
  out.mean = sum / static_cast<double>(values.size());
  if (values.size() < 2) return out;
  double squares = 0.0;
  for (double v : values) squares += (v - out.mean) * (v - out.mean);
  out.sd = std::sqrt(squares / static_cast<double>(values.size() - 1));
  return out;
}

ImpactZonesSummary summariseZones(const std::vector<ZoneBackwardSample>& samples) {
  ImpactZonesSummary s;
  s.zones = static_cast<int>(samples.size());
  std::vector<double> kktSize, qrSize, kktSeconds, qrSeconds, ratios;
  for (const ZoneBackwardSample& z : samples) {
    kktSize.push_back(z.n + z.m);
    qrSize.push_back(z.rank);
    kktSeconds.push_back(z.kktSeconds);
    qrSeconds.push_back(z.qrSeconds);
    if (z.qrSeconds > 0.0) ratios.push_back(z.kktSeconds / z.qrSeconds);
    s.kktSingular += !z.kktOk;
    s.rankDeficient += z.rank < z.active;
    s.withoutActive += z.active == 0;
    s.degenerate += z.tightWithoutMultiplier > 0;
    if (z.kktOk) {
      s.maxDifferenceDx = std::max(s.maxDifferenceDx, z.differenceDx);
      s.maxDifferenceAll = std::max(s.maxDifferenceAll, z.differenceAll);
    }
  }
  s.kktSize = meanSd(kktSize);
  s.qrSize = meanSd(qrSize);
  s.kktSeconds = meanSd(kktSeconds);
  s.qrSeconds = meanSd(qrSeconds);
  s.sizeRatio = s.qrSize.mean > 0.0 ? s.kktSize.mean / s.qrSize.mean : 0.0;
  s.speedup = s.qrSeconds.mean > 0.0 ? s.kktSeconds.mean / s.qrSeconds.mean : 0.0;
  s.medianSpeedup = median(ratios);
  return s;
}

int runImpactZonesBench(const ImpactZonesBenchOptions& options, const std::string& outDir) {
  const bool quick = options.quick;
  omp_set_num_threads(options.threads);
  StagedDirectory out(outDir);
  const std::vector<int> resolutions = !options.resolutions.empty() ? options.resolutions
                                       : quick                      ? std::vector<int>{8, 16}
                                                                    : std::vector<int>{16, 32, 64};
  const int steps = options.steps > 0 ? options.steps : quick ? kQuickSteps : kSteps;
  const double minSeconds = quick ? kQuickMinSeconds : kMinSeconds;

  // clang-format off
  BenchTable table({"quads", "vertices", "steps", "zone_qps", "sparse_zones", "rigid_zones", "kkt_size", "qr_size",
                    "kkt_ms", "qr_ms", "size_ratio", "speedup", "median_speedup", "kkt_singular",
                    "tight_zero_lambda", "rank_deficient", "no_active_rows", "max_rel_diff_dx", "max_rel_diff_all",
                    "forward_s", "response_s", "unresolved_steps", "split_steps",
                    "states_with_crossings", "max_move_mm", "failed_step"});
  BenchTable zones({"quads", "step", "n", "m", "active", "rank", "kkt_size", "kkt_ms", "qr_ms",
                    "kkt_ok", "rel_diff_dx", "rel_diff_all", "tight_zero_lambda"});
  // clang-format on
  std::vector<PlotSeries> plot;
  const auto start = Clock::now();
  for (int q : resolutions) {
    std::fprintf(stderr, "impact_zones: %dx%d, %d steps\n", q, q, steps);
    const ResolutionRun r = runResolution(q, steps, minSeconds);
    const ImpactZonesSummary s = summariseZones(r.samples);
    table.add({std::to_string(q),
               std::to_string(r.vertices),
               std::to_string(r.steps),
               std::to_string(s.zones),
               std::to_string(r.sparseZones),
               std::to_string(r.rigidZones),
               meanSdText(s.kktSize, 4),
               meanSdText(s.qrSize, 3),
               meanSdText({1e3 * s.kktSeconds.mean, 1e3 * s.kktSeconds.sd}, 3),
               meanSdText({1e3 * s.qrSeconds.mean, 1e3 * s.qrSeconds.sd}, 3),
               formatNumber(s.sizeRatio, 3),
               formatNumber(s.speedup, 3),
               formatNumber(s.medianSpeedup, 3),
               std::to_string(s.kktSingular),
               std::to_string(s.degenerate),
               std::to_string(s.rankDeficient),
               std::to_string(s.withoutActive),
               formatNumber(s.maxDifferenceDx, 2),
               formatNumber(s.maxDifferenceAll, 2),
               formatNumber(r.forwardSeconds, 3),
               formatNumber(r.responseSeconds, 3),
               std::to_string(r.unresolvedSteps),
               std::to_string(r.splitSteps),
               std::to_string(r.statesWithCrossings),
               formatNumber(1e3 * r.maxMove, 3),
               std::to_string(r.failedStep)});
    PlotSeries kkt{std::to_string(q) + "² KKT (Eq. 13)", {}, {}, "points"};
    PlotSeries qr{std::to_string(q) + "² QR (Sec. 3.4.1)", {}, {}, "points"};
    for (std::size_t i = 0; i < r.samples.size(); ++i) {
      const ZoneBackwardSample& z = r.samples[i];
      zones.add({std::to_string(q), std::to_string(r.sampleStep[i]), std::to_string(z.n),
                 std::to_string(z.m), std::to_string(z.active), std::to_string(z.rank),
                 std::to_string(z.n + z.m), formatNumber(1e3 * z.kktSeconds),
                 formatNumber(1e3 * z.qrSeconds), z.kktOk ? "1" : "0",
                 z.kktOk ? formatNumber(z.differenceDx, 2) : "",
                 z.kktOk ? formatNumber(z.differenceAll, 2) : "",
                 std::to_string(z.tightWithoutMultiplier)});
      kkt.x.push_back(z.n + z.m);
      kkt.y.push_back(1e3 * z.kktSeconds);
      qr.x.push_back(z.n + z.m);
      qr.y.push_back(1e3 * z.qrSeconds);
    }
    plot.push_back(kkt);
    plot.push_back(qr);
  }
  const double seconds = since(start);

  const std::string preamble =
      "Scene assets/" + std::string(kScene) +
      " (a cloth dropped into an upside-down square pyramid, a mesh obstacle) with "
      "cloths.0.self_collision {\"model\": \"impact_zones\", \"thickness\": " +
      formatNumber(kThickness, 6) + "}, the grid overridden to n x n quads, " +
      std::to_string(steps) + " steps of 5 ms, " + std::to_string(options.threads) +
      " thread(s) for the forward run. Every final zone of every accepted step (zone_qps; "
      "sparse_zones of them were solved by the sparse method and are differentiated in their "
      "dense form; rigid_zones, moved by the failsafe's translation, have no QP and are not "
      "among them) is differentiated by both routes with the same dL/dz (standard normal "
      "entries, fixed seed), each call repeated for at least " +
      formatNumber(1e3 * minSeconds, 3) +
      " ms. kkt_size: n + m, the order of Liang Eq. 13's matrix (dense LU with full pivoting, "
      "zoneQpGradientKkt); qr_size: the numerical rank of the rows with lambda > 0, the order of "
      "R_1 (zoneQpGradientQr, Eqs. 17-21); mean ± sample standard deviation over the zones, "
      "times in ms per QP backward. size_ratio and speedup: ratios of the means (as the paper's "
      "Table 1); median_speedup: the median over zones of the per-zone ratio. kkt_singular: "
      "zones whose Eq. 13 matrix was singular (their LU time is counted, the QR route still "
      "gives a gradient); tight_zero_lambda: zones with a row tight at the solution "
      "(|G_j z + h_j| <= 1e-9 of its terms) whose multiplier is 0, the degenerate case that "
      "makes Eq. 13's matrix singular; rank_deficient: zones whose active rows are linearly "
      "dependent; "
      "max_rel_diff_*: the largest max |QR - KKT| / max |KKT| over the zones where both routes "
      "gave a gradient, over dL/dx alone and over dL/dx, dL/dG, dL/dh. forward_s: the forward "
      "run's wall seconds (without the timings above), response_s the impact-zone response's "
      "part of it; unresolved_steps, split_steps, states_with_crossings, max_move_mm: the "
      "forward run's health (weft simulate's stats.csv columns). " +
      formatNumber(seconds, 3) + " s in all. Machine: " + machineDescription() + ".";
  table.writeCsv(out.file("impact_zones.csv"));
  zones.writeCsv(out.file("zones.csv"));
  {
    std::ofstream md(out.file("impact_zones.md"));
    table.writeMarkdown(md, "Impact-zone QP backward: KKT against QR (weft bench impact_zones)",
                        preamble);
    md << "\n### Liang et al. 2019, Table 1 (their numbers)\n\n"
       << "| quads | kkt_size | kkt_s | qr_size | qr_s | size_ratio | speedup |\n"
       << "| ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n"
       << "| 16 | 599 ± 76 | 0.33 ± 0.13 | 66 ± 26 | 0.013 ± 0.0019 | 8.9 | 25 |\n"
       << "| 32 | 1326 ± 23 | 1.2 ± 0.10 | 97 ± 24 | 0.011 ± 0.0023 | 13 | 112 |\n"
       << "| 64 | 2024 ± 274 | 4.6 ± 0.33 | 242 ± 47 | 0.072 ± 0.011 | 8.3 | 64 |\n";
    if (!md) throw InputError(out.file("impact_zones.md"), "output", "write failed");
  }
  std::string reason;
  if (!plotSeries(out.file("impact_zones.png"), "Impact-zone QP backward per zone",
                  "KKT matrix size n + m", "ms per QP backward", plot, true, true, reason))
    std::fprintf(stderr, "warning: %s\n", reason.c_str());
  out.commit();
  std::printf("bench impact_zones: %zu resolutions in %.1f s -> %s/impact_zones.{csv,md,png}\n",
              table.rows().size(), seconds, outDir.c_str());
  return 0;
}

}  // namespace weft::bench
