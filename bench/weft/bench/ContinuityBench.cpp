// `weft bench continuity`: DiffCloth's Fig. 2 experiment (Sec. 5.1). A cloth lies on a static
// frictional sphere; the friction coefficient mu is swept from 0 to 0.35 and the speeds of a
// corner node (A), an edge-centre node (B) and the centre node (C) are recorded at steps 50 and
// 200. With the analytic sphere the curves should be continuous in mu: switching between the
// take-off, stick and slip branches does not make the step jump. With a triangulated sphere
// and flat face normals the contact frame jumps across triangle edges, and so do the curves;
// smoothed (interpolated vertex) normals are the remedy the paper suggests.
//
// A curve sampled at spacing d has neighbour differences of about slope * d where it is
// continuous, and a difference that does not shrink with d at a jump. The summary therefore
// reports, per curve, the largest neighbour difference, its ratio to the median one, and its
// ratio to the largest difference at twice the spacing (about 0.5 continuous, about 1 a jump).
//
// --contact scene|pd|newton|active_set sets solver.contact for every run (default newton, which
// converges these steps in a few solves; "scene" keeps the scene's own); --subdivisions the
// triangulated sphere's (default 2, 320 triangles); --resolution the cloth's quads per side;
// a speed read after steps that ended above solver.pd_tolerance carries their unconverged part,
// so the summary also gives the largest count of such steps over the mu samples.

#include "ContinuityBench.h"

#include "BenchAssets.h"
#include "BenchTable.h"
#include "Icosphere.h"

#include <weft/core/Error.h>
#include <weft/io/StagedDirectory.h>
#include <weft/mesh/SphereProjection.h>
#include <weft/physics/Simulator.h>
#include <weft/scene/SceneLoader.h>

#include <omp.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

namespace weft::bench {
namespace {

enum class Surface { Analytic, FlatMesh, SmoothMesh };

const char* surfaceName(Surface s) {
  switch (s) {
    case Surface::Analytic:
      return "analytic";
    case Surface::FlatMesh:
      return "mesh_flat";
    case Surface::SmoothMesh:
      return "mesh_smooth";
  }
  return "?";
}

struct Probe {
  const char* label;  // the paper's node names
  int vertex;
};

// Speeds of the probes at each recorded step, and the contact branches at that step.
struct Sample {
  std::vector<std::vector<double>> speed;    // [recorded step][probe]
  std::vector<std::array<int, 3>> branches;  // [recorded step] takeoff, stick, slip
  // [recorded step] steps so far whose PD iterations stopped at the cap, not the tolerance
  std::vector<int> unconverged;
  int failedStep = 0;  // the step that threw a NumericalError, 0 if none
};

// The cloth's horizontal extent spans polar angles on the sphere from asin(0.05) to asin(0.37),
// whose tangents (the friction a node needs to stick there on its own) run from 0.05 to 0.40:
// the paper's sweep over [0, 0.35] then crosses from sliding to sticking.
constexpr double kNearEdge = 0.05, kFarEdge = 0.37;

// Fig. 2's setting, from the scene's cloth, material, time step and solver: the cloth lies on
// the sphere (laid onto it by projectOntoSphere, so its rest shape is the curved patch: it
// starts unstretched, at rest and with every node in contact) and slides down one side, without
// self-collision (the experiment isolates contact with the sphere). The sphere keeps the
// scene's centre; its radius is scaled to the cloth (kNearEdge, kFarEdge), so that with large
// friction every node sticks and with little the whole cloth slides, as the paper describes.
// The triangulated spheres are inscribed in the analytic one, so the cloth starts up to their
// sagitta above their faces and settles onto them in the first steps.
Scene makeScene(const std::string& file, Surface surface, int subdivisions, double mu, int steps,
                const std::string& contact, int resolution) {
  std::vector<SceneOverride> overrides = {{"time.steps", std::to_string(steps)}};
  if (contact != "scene") overrides.push_back({"solver.contact", "\"" + contact + "\""});
  if (resolution > 0) {
    const std::string r = std::to_string(resolution);
    overrides.push_back({"cloths.0.mesh.grid.resolution", "[" + r + "," + r + "]"});
  }
  Scene scene = loadScene(file, overrides);
  if (scene.cloths.size() != 1 || scene.obstacles.size() != 1 ||
      scene.obstacles[0].shape != Obstacle::Shape::Sphere)
    throw InputError(file, "obstacles",
                     "the continuity benchmark needs one cloth and one sphere obstacle");
  Obstacle& sphere = scene.obstacles[0];
  sphere.friction = mu;
  Cloth& cloth = scene.cloths[0];
  cloth.selfCollision.reset();
  NodeMatrix& x = cloth.mesh.vertices;
  if (x.col(1).maxCoeff() - x.col(1).minCoeff() > 1e-9)
    throw InputError(file, "cloths.0.mesh",
                     "the continuity benchmark needs a flat grid cloth in the XZ plane");
  const double width = x.col(0).maxCoeff() - x.col(0).minCoeff();
  sphere.radius = width / (kFarEdge - kNearEdge);
  const double x0 = sphere.center.x() + kNearEdge * sphere.radius - x.col(0).minCoeff();
  const double z0 = sphere.center.z() - 0.5 * (x.col(2).maxCoeff() + x.col(2).minCoeff());
  x.col(0).array() += x0;
  x.col(2).array() += z0;
  cloth.mesh = projectOntoSphere(cloth.mesh, sphere.center, sphere.radius + sphere.thickness);
  if (surface != Surface::Analytic) {
    sphere.mesh = icosphere(sphere.center, sphere.radius, subdivisions);
    sphere.shape = Obstacle::Shape::Mesh;
    sphere.smoothNormals = surface == Surface::SmoothMesh;
  }
  return scene;
}

Sample simulate(const Scene& scene, const std::vector<Probe>& probes,
                const std::vector<int>& recordAt) {
  Sample sample;
  Simulator sim(scene);
  try {
    int unconverged = 0;
    for (int step = 1; step <= recordAt.back(); ++step) {
      const StepStats& stats = sim.step();
      unconverged += !stats.converged;
      if (std::find(recordAt.begin(), recordAt.end(), step) == recordAt.end()) continue;
      std::vector<double> row;
      for (const Probe& p : probes) row.push_back(sim.velocities().row(p.vertex).norm());
      sample.speed.push_back(row);
      sample.branches.push_back({stats.takeoff, stats.stick, stats.slip});
      sample.unconverged.push_back(unconverged);
    }
  } catch (const NumericalError& e) {
    sample.failedStep = sim.stepIndex() + 1;
    std::fprintf(stderr, "continuity: numerical failure: %s\n", e.what());
    const std::vector<double> nan(probes.size(), std::numeric_limits<double>::quiet_NaN());
    while (sample.speed.size() < recordAt.size()) {
      sample.speed.push_back(nan);
      sample.branches.push_back({0, 0, 0});
      sample.unconverged.push_back(0);
    }
  }
  return sample;
}

}  // namespace

int runContinuityBench(const ContinuityBenchOptions& options, const std::string& outDir) {
  const bool quick = options.quick;
  const std::string file = options.scene.empty() ? assetFile("scenes/sphere.json") : options.scene;
  const int threads = options.threads;
  const std::string contact = options.contact;
  omp_set_num_threads(threads);
  StagedDirectory out(outDir);

  // The paper sweeps mu over [0, 0.35] and reads steps 50 and 200; 29 samples (spacing 0.0125) keep
  // the run under 10 minutes. Quick: 5 samples, steps 10 and 20 (enough to exercise every code path
  // in a test).
  const int samples = quick ? 5 : 29;
  const std::vector<int> recordAt = quick ? std::vector<int>{10, 20} : std::vector<int>{50, 200};
  // 320 triangles: on the scaled sphere an edge is about 0.8 of the cloth's width and
  // neighbouring faces meet at about 15 degrees.
  const int subdivisions = options.subdivisions;
  const int resolution = options.resolution;  // 0: the scene's grid
  const std::vector<Surface> surfaces = {Surface::Analytic, Surface::FlatMesh, Surface::SmoothMesh};

  const Scene probeScene =
      makeScene(file, Surface::Analytic, subdivisions, 0.0, recordAt.back(), contact, resolution);
  // Grid vertex (i, j) is j * (n + 1) + i: corner, middle of the first row, centre.
  const int vertices = probeScene.cloths[0].mesh.vertexCount();
  const int side = static_cast<int>(std::lround(std::sqrt(double(vertices))));
  if (side * side != vertices)
    throw InputError(file, "cloths.0.mesh", "the continuity benchmark needs a square grid cloth");
  const int n = side - 1;
  const std::vector<Probe> probes = {
      {"A_corner", 0}, {"B_edge", n / 2}, {"C_centre", (n / 2) * side + n / 2}};

  BenchTable table({"surface", "mu", "step", "node", "vertex", "speed", "takeoff", "stick", "slip",
                    "unconverged_steps", "failed_step"});
  // curves[surface][recorded step][probe] = speeds over mu
  std::vector<std::vector<std::vector<std::vector<double>>>> curves(
      surfaces.size(), std::vector<std::vector<std::vector<double>>>(
                           recordAt.size(), std::vector<std::vector<double>>(probes.size())));
  // unconvergedMax[surface][recorded step]: the most steps at the iteration cap over mu
  std::vector<std::vector<int>> unconvergedMax(surfaces.size(),
                                               std::vector<int>(recordAt.size(), 0));
  std::vector<double> mus;
  for (int k = 0; k < samples; ++k) mus.push_back(0.35 * k / (samples - 1));
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t s = 0; s < surfaces.size(); ++s) {
    for (double mu : mus) {
      std::fprintf(stderr, "\rcontinuity: %s mu %.4f   ", surfaceName(surfaces[s]), mu);
      const Sample sample = simulate(
          makeScene(file, surfaces[s], subdivisions, mu, recordAt.back(), contact, resolution),
          probes, recordAt);
      for (std::size_t r = 0; r < recordAt.size(); ++r) {
        unconvergedMax[s][r] = std::max(unconvergedMax[s][r], sample.unconverged[r]);
        for (std::size_t p = 0; p < probes.size(); ++p) {
          curves[s][r][p].push_back(sample.speed[r][p]);
          table.add({surfaceName(surfaces[s]), formatNumber(mu, 6), std::to_string(recordAt[r]),
                     probes[p].label, std::to_string(probes[p].vertex),
                     formatNumber(sample.speed[r][p], 8), std::to_string(sample.branches[r][0]),
                     std::to_string(sample.branches[r][1]), std::to_string(sample.branches[r][2]),
                     std::to_string(sample.unconverged[r]), std::to_string(sample.failedStep)});
        }
      }
    }
  }
  std::fprintf(stderr, "\n");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // Per curve: the largest difference between neighbouring mu samples, where it is, its ratio to
  // the median nonzero difference (a stuck cloth's zero speeds are not a scale), and how the
  // largest difference shrinks when the spacing halves: against every second sample, a
  // continuous curve gives about 0.5 (its steepest slope times the spacing), a jump about 1.
  BenchTable summary({"surface", "step", "node", "max_jump", "at_mu", "median_jump", "jump_ratio",
                      "halving_ratio", "speed_range", "unconverged_max"});
  const auto largestJump = [](const std::vector<double>& c, std::size_t stride) {
    double worst = 0.0;
    for (std::size_t k = stride; k < c.size(); k += stride)
      worst = std::max(worst, std::abs(c[k] - c[k - stride]));
    return worst;
  };
  for (std::size_t s = 0; s < surfaces.size(); ++s)
    for (std::size_t r = 0; r < recordAt.size(); ++r)
      for (std::size_t p = 0; p < probes.size(); ++p) {
        const std::vector<double>& c = curves[s][r][p];
        const auto [lo, hi] = std::minmax_element(c.begin(), c.end());
        const double range = *hi - *lo;
        std::vector<double> jumps;
        double worst = 0.0, at = 0.0;
        for (std::size_t k = 1; k < c.size(); ++k) {
          const double d = std::abs(c[k] - c[k - 1]);
          if (d > 1e-9 * range) jumps.push_back(d);
          if (!(d <= worst)) worst = d, at = 0.5 * (mus[k] + mus[k - 1]);
        }
        const double med = median(jumps);
        const double coarse = largestJump(c, 2);
        summary.add({surfaceName(surfaces[s]), std::to_string(recordAt[r]), probes[p].label,
                     formatNumber(worst, 4), formatNumber(at, 4), formatNumber(med, 4),
                     formatNumber(med > 0 ? worst / med : 0.0, 3),
                     formatNumber(coarse > 0 ? worst / coarse : 0.0, 3), formatNumber(range, 4),
                     std::to_string(unconvergedMax[s][r])});
      }

  const std::string preamble =
      "DiffCloth Fig. 2 (Sec. 5.1): cloth of " + file + " (" + std::to_string(n) + "x" +
      std::to_string(n) + " quads) lying on a sphere of radius " +
      formatNumber(probeScene.obstacles[0].radius, 4) +
      " m (the cloth spans polar angles with tangents 0.05 to 0.40), at rest and unstretched, "
      "without self-collision, solver.contact " +
      (contact == "scene" ? std::string("as in the scene") : "\"" + contact + "\"") +
      ", h = " + formatNumber(probeScene.time.dt, 4) + " s. Friction mu swept over [0, 0.35] in " +
      std::to_string(samples) +
      " samples; speeds (m/s) of the corner A, edge-centre B and centre C nodes at the listed "
      "steps (unconverged_steps: steps so far that ended above solver.pd_tolerance). Surfaces: the "
      "analytic sphere; an icosphere of " +
      std::to_string(20 << (2 * subdivisions)) +
      " triangles with flat face normals; the same with smoothed (interpolated vertex) normals. " +
      std::to_string(threads) + " thread(s), " + formatNumber(seconds, 3) +
      " s in all. Machine: " + machineDescription() + ".";
  table.writeCsv(out.file("continuity.csv"));
  summary.writeCsv(out.file("continuity_summary.csv"));
  // The Markdown carries the per-curve summary; every sample is in continuity.csv.
  summary.writeMarkdown(
      out.file("continuity.md"), "Continuity of contact branches (weft bench continuity)",
      preamble +
          "\n\nPer curve, the largest speed difference between neighbouring mu samples "
          "(max_jump, at_mu), the median nonzero one, jump_ratio = max_jump / median_jump, and "
          "halving_ratio = max_jump / the largest difference between every second sample. A "
          "continuous curve keeps jump_ratio moderate (kinks at branch switches included) and "
          "halving_ratio near 0.5 (halving the spacing halves its differences); a discontinuity "
          "shows as a jump far above the median that does not shrink with the spacing "
          "(halving_ratio "
          "near 1). unconverged_max: the most steps, up to the listed one, that ended above "
          "solver.pd_tolerance, over the mu samples. Every sample: continuity.csv; plots: "
          "continuity_step*.png.");
  for (std::size_t r = 0; r < recordAt.size(); ++r) {
    std::vector<PlotSeries> plot;
    for (std::size_t s = 0; s < surfaces.size(); ++s)
      for (std::size_t p = 0; p < probes.size(); ++p)
        plot.push_back(
            {std::string(surfaceName(surfaces[s])) + " " + probes[p].label, mus, curves[s][r][p]});
    std::string reason;
    const std::string png = out.file("continuity_step" + std::to_string(recordAt[r]) + ".png");
    if (!plotSeries(png, "Node speed at step " + std::to_string(recordAt[r]) + " vs friction", "mu",
                    "speed (m/s)", plot, false, false, reason))
      std::fprintf(stderr, "warning: %s\n", reason.c_str());
  }
  out.commit();
  std::printf(
      "bench continuity: %zu runs (%d mu samples x %zu surfaces) in %.1f s -> "
      "%s/continuity.{csv,md}\n",
      mus.size() * surfaces.size(), samples, surfaces.size(), seconds, outDir.c_str());
  return 0;
}

}  // namespace weft::bench
