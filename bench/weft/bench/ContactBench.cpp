// `weft bench contact`: what contact costs. Seconds per step split by module (the PD solve with
// its energies and forces, obstacle contact detection, self-collision detection, the
// Signorini-Coulomb contact solve) for the Sphere, Slope and Crumple scenes at 24^2, 48^2 and
// 96^2 quads, single-threaded; how the contact cost grows with the number of contacts; and the
// peak resident memory of each run.
//
// Peak memory per run: Linux resets a process's peak RSS (VmHWM) when "5" is written to
// /proc/self/clear_refs, so each run's peak is read from /proc/self/status after resetting it
// before the run. The runs step the simulator without recording a trajectory (its cost is
// steps x vertices x 48 bytes for positions and velocities, plus the contacts, and is the
// caller's choice); the table gives that figure separately.

#include "ContactBench.h"

#include "BenchAssets.h"
#include "BenchTable.h"
#include "ProcessMemory.h"

#include <weft/core/Error.h>
#include <weft/core/ProcessCpuTime.h>
#include <weft/io/StagedDirectory.h>
#include <weft/physics/Simulator.h>
#include <weft/scene/SceneLoader.h>

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace weft::bench {
namespace {

struct RunResult {
  int vertices = 0, steps = 0, failedStep = 0;
  double secondsPerStep = 0.0;
  // The median step's wall time: the steady cost, without the one-off work a mean spreads over
  // the run (the first factorisations, the landing on the obstacle).
  double medianStepSeconds = 0.0;
  double pd = 0.0, detection = 0.0, selfCollision = 0.0, contactSolve = 0.0;  // s per step
  double meanContacts = 0.0;
  int maxContacts = 0;
  int endTakeoff = 0, endStick = 0, endSlip = 0;
  double pdIterations = 0.0;
  int convergedSteps = 0;
  double worstResidual = 0.0;  // m/s^2, the largest residual a step ended with
  double maxDepth = 0.0;       // m, the deepest node inside an obstacle's skin (StepStats::depth)
  int splitSteps = 0;          // steps adaptive time stepping split (StepStats::substeps > 1)
  double cpuSeconds = 0.0;     // the run's process CPU time, all threads
  // Contact-solve seconds per contact per Gauss-Seidel sweep: the solve's unit cost, apart
  // from how many sweeps the PD iterations asked for.
  double solvePerContactSweep = 0.0;
  double peakMb = 0.0;
  // Per step: contacts and seconds of the contact solve (for the growth fit).
  std::vector<double> stepContacts, stepSolveSeconds;
};

RunResult runScene(const std::string& file, int quads, int steps, const std::string& contact) {
  const std::string res = "[" + std::to_string(quads) + "," + std::to_string(quads) + "]";
  std::vector<SceneOverride> overrides = {{"cloths.0.mesh.grid.resolution", res},
                                          {"time.steps", std::to_string(steps)}};
  const std::string whole = "-whole";
  const bool isWhole = contact.size() > whole.size() &&
                       contact.compare(contact.size() - whole.size(), whole.size(), whole) == 0;
  const std::string solve = isWhole ? contact.substr(0, contact.size() - whole.size()) : contact;
  if (solve != "scene") overrides.push_back({"solver.contact", "\"" + solve + "\""});
  if (isWhole) overrides.push_back({"solver.max_halvings", "0"});
  Scene scene = loadScene(file, overrides);
  RunResult r;
  r.vertices = scene.vertexCount();
  Simulator sim(scene);
  const std::vector<std::string>& names = sim.moduleNames();
  long long iterations = 0, contacts = 0;
  double contactSweeps = 0.0, solveSeconds = 0.0;
  std::vector<double> stepSeconds;
  const auto start = std::chrono::steady_clock::now();
  const double cpuStart = processCpuSeconds();
  try {
    for (int s = 0; s < steps; ++s) {
      const auto stepStart = std::chrono::steady_clock::now();
      const StepStats& st = sim.step();
      stepSeconds.push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - stepStart).count());
      const int c = st.takeoff + st.stick + st.slip;
      contacts += c;
      r.maxContacts = std::max(r.maxContacts, c);
      iterations += st.pdIterations;
      r.convergedSteps += st.converged;
      r.worstResidual = std::max(r.worstResidual, st.residual);
      r.maxDepth = std::max(r.maxDepth, st.depth);
      r.splitSteps += st.substeps > 1;
      r.endTakeoff = st.takeoff, r.endStick = st.stick, r.endSlip = st.slip;
      double solve = 0.0;
      for (std::size_t m = 0; m < names.size(); ++m)
        if (names[m] == "contact_solve") solve = st.moduleSeconds[m];
      contactSweeps += double(c) * st.contactSweeps;
      solveSeconds += solve;
      r.stepContacts.push_back(c);
      r.stepSolveSeconds.push_back(solve);
      ++r.steps;
    }
  } catch (const NumericalError& e) {
    r.failedStep = r.steps + 1;
    std::fprintf(stderr, "\ncontact: numerical failure: %s\n", e.what());
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.cpuSeconds = processCpuSeconds() - cpuStart;
  const double n = std::max(1, r.steps);
  r.secondsPerStep = seconds / n;
  r.medianStepSeconds = median(stepSeconds);
  for (std::size_t m = 0; m < names.size(); ++m) {
    const double t = sim.moduleSeconds()[m] / n;
    if (names[m] == "contact_detection")
      r.detection = t;
    else if (names[m] == "self_collision")
      r.selfCollision = t;
    else if (names[m] == "contact_solve")
      r.contactSolve = t;
    else
      r.pd += t;  // the solver and every energy and force it evaluates
  }
  r.meanContacts = double(contacts) / n;
  r.solvePerContactSweep = contactSweeps > 0 ? solveSeconds / contactSweeps : 0.0;
  r.pdIterations = double(iterations) / n;
  return r;
}

// Least-squares slope of log(y) against log(x) over the points with x, y > 0.
double logLogSlope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!(x[i] > 0 && y[i] > 0)) continue;
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly, ++n;
  }
  const double d = n * sxx - sx * sx;
  return n >= 2 && d > 1e-12 ? (n * sxy - sx * sy) / d : std::nan("");
}

}  // namespace

int runContactBench(const ContactBenchOptions& options, const std::string& outDir) {
  const bool quick = options.quick;
  const int threads = options.threads;
  omp_set_num_threads(threads);
  StagedDirectory out(outDir);

  struct Case {
    const char* name;
    std::string file;
    int steps;  // long enough for the cloth to reach its contact-rich phase; Slope: the scene's own
                // 300
  };
  const std::vector<Case> allCases = {{"sphere", assetFile("scenes/sphere.json"), 150},
                                      {"slope", assetFile("scenes/slope.json"), 300},
                                      {"crumple", assetFile("scenes/crumple.json"), 150}};
  std::vector<Case> cases;
  for (const std::string& name : options.scenes.empty() ? kContactBenchScenes : options.scenes)
    for (const Case& c : allCases)
      if (name == c.name) cases.push_back(c);
  const std::vector<int> resolutions = !options.resolutions.empty() ? options.resolutions
                                       : quick                      ? std::vector<int>{8, 16}
                                                                    : std::vector<int>{24, 48, 96};
  // --contact pd,newton runs every case with each contact solve (solver.contact), so that their
  // costs are compared in one command; "scene" (the default) keeps each scene's own setting.
  const std::vector<std::string> contactMethods =
      options.contacts.empty() ? std::vector<std::string>{"scene"} : options.contacts;
  const int quickSteps = 40;  // the sphere and crumple cloths reach their obstacle by then
  const bool peakResets = resetPeakMemory();

  // clang-format off
  BenchTable table({"scene", "contact", "quads", "vertices", "steps", "ms_per_step", "ms_median_step", "ms_pd", "ms_detection",
                    "ms_self_collision", "ms_contact_solve", "contacts_mean", "contacts_max",
                    "takeoff_end", "stick_end", "slip_end", "us_solve_per_contact",
                    "ns_per_contact_sweep", "pd_iterations", "converged_steps", "worst_residual",
                    "max_depth_mm", "split_steps", "cpu_s", "peak_mb",
                    "trajectory_mb", "failed_step"});
  // clang-format on
  std::vector<PlotSeries> costPlot, modulePlot;
  std::ostringstream growth;
  const auto start = std::chrono::steady_clock::now();
  for (const Case& c : cases) {
    PlotSeries cost{std::string(c.name) + " contact ms", {}, {}};
    PlotSeries self{std::string(c.name) + " self-collision ms", {}, {}};
    std::vector<double> allContacts, allSolve;
    for (int q : resolutions)
      for (const std::string& contact : contactMethods) {
        const int steps = quick ? quickSteps : c.steps;
        std::fprintf(stderr, "contact: %s %dx%d (%s), %d steps\n", c.name, q, q, contact.c_str(),
                     steps);
        resetPeakMemory();
        const RunResult r = runScene(c.file, q, steps, contact);
        const double peak = peakResets ? peakMemoryMb() : 0.0;
        const double contactMs = 1e3 * (r.detection + r.selfCollision + r.contactSolve);
        // Positions and velocities of every state (2 x 3 doubles per vertex per state); the
        // recorded contacts come on top.
        const double trajectoryMb = 48.0 * r.vertices * (steps + 1) / (1024.0 * 1024.0);
        table.add({c.name,
                   contact,
                   std::to_string(q),
                   std::to_string(r.vertices),
                   std::to_string(r.steps),
                   formatNumber(1e3 * r.secondsPerStep),
                   formatNumber(1e3 * r.medianStepSeconds),
                   formatNumber(1e3 * r.pd),
                   formatNumber(1e3 * r.detection),
                   formatNumber(1e3 * r.selfCollision),
                   formatNumber(1e3 * r.contactSolve),
                   formatNumber(r.meanContacts),
                   std::to_string(r.maxContacts),
                   std::to_string(r.endTakeoff),
                   std::to_string(r.endStick),
                   std::to_string(r.endSlip),
                   formatNumber(r.meanContacts > 0 ? 1e6 * r.contactSolve / r.meanContacts : 0.0),
                   formatNumber(1e9 * r.solvePerContactSweep),
                   formatNumber(r.pdIterations),
                   std::to_string(r.convergedSteps),
                   formatNumber(r.worstResidual, 3),
                   formatNumber(1e3 * r.maxDepth, 3),
                   std::to_string(r.splitSteps),
                   formatNumber(r.cpuSeconds, 3),
                   peakResets ? formatNumber(peak) : "n/a",
                   formatNumber(trajectoryMb),
                   std::to_string(r.failedStep)});
        if (r.meanContacts > 0) {
          cost.x.push_back(r.meanContacts);
          cost.y.push_back(std::max(contactMs, 1e-6));
        }
        if (r.selfCollision > 0) {
          self.x.push_back(r.vertices);
          self.y.push_back(1e3 * r.selfCollision);
        }
        allContacts.insert(allContacts.end(), r.stepContacts.begin(), r.stepContacts.end());
        allSolve.insert(allSolve.end(), r.stepSolveSeconds.begin(), r.stepSolveSeconds.end());
      }
    costPlot.push_back(cost);
    if (!self.x.empty()) modulePlot.push_back(self);
    growth << "| " << c.name << " | " << formatNumber(logLogSlope(allContacts, allSolve), 3)
           << " | " << formatNumber(logLogSlope(self.x, self.y), 3) << " |\n";
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const std::string preamble =
      "Scenes assets/scenes/{sphere,slope,crumple}.json with the cloth grid overridden to n x n "
      "quads, each run for the listed steps from the scene's start, " +
      std::to_string(threads) +
      " thread(s). contact: the contact solve (solver.contact; scene = the scene file's own, "
      "newton for all three; -whole: adaptive time stepping off, solver.max_halvings 0). "
      "ms_per_step is the mean over the run's steps, "
      "ms_median_step the median step (without the one-off work the mean spreads over the run: "
      "the first factorisations, the landing). The other ms_* are milliseconds per step by module: "
      "ms_pd is the PD solve with the "
      "energies and forces it evaluates, ms_detection obstacle contact detection, "
      "ms_self_collision node-node self-collision detection, ms_contact_solve the "
      "Signorini-Coulomb solve (and, for newton, its linearisation). Contacts count node-obstacle "
      "contacts and "
      "self-collision pairs per step; ns_per_contact_sweep is the contact solve's time per "
      "contact per Gauss-Seidel sweep (its unit cost, apart from how many sweeps the PD "
      "iterations ask for). converged_steps: steps that reached solver.pd_tolerance, the others "
      "stopped at solver.pd_iterations; worst_residual: the largest residual a step ended with "
      "(m/s^2); max_depth_mm: the deepest node inside an obstacle's contact skin at the end of "
      "any step; split_steps: steps adaptive time stepping solved in pieces (solver.max_halvings); "
      "cpu_s: the run's CPU seconds. peak_mb: peak resident memory of the run (the process's "
      "VmHWM, reset "
      "before it; it includes the program itself), stepping without a recorded trajectory; "
      "trajectory_mb: what recording positions and velocities of every state would add. " +
      formatNumber(seconds, 3) + " s in all. Machine: " + machineDescription() + ".";
  table.writeCsv(out.file("contact.csv"));
  table.writeMarkdown(out.file("contact.md"), "Contact cost by module (weft bench contact)",
                      preamble);
  {
    std::ofstream md(out.file("contact.md"), std::ios::app);
    md << "\n### Growth exponents\n\n"
       << "Least-squares slopes in log-log: contact-solve seconds of a step against its number of "
          "contacts (all "
          "steps with contacts, all resolutions), and self-collision seconds per step against the "
          "vertex count "
          "(1 = linear).\n\n| scene | solve vs contacts | self-collision vs vertices |\n| --- | "
          "---: | ---: |\n"
       << growth.str();
  }
  std::string reason;
  if (!plotSeries(out.file("contact.png"), "Contact cost per step vs contacts per step",
                  "contacts per step (mean)",
                  "contact ms per step (detection + self-collision + solve)", costPlot, true, true,
                  reason))
    std::fprintf(stderr, "warning: %s\n", reason.c_str());
  if (!modulePlot.empty() &&
      !plotSeries(out.file("contact_self_collision.png"), "Self-collision detection vs vertices",
                  "vertices", "ms per step", modulePlot, true, true, reason))
    std::fprintf(stderr, "warning: %s\n", reason.c_str());
  out.commit();
  std::printf("bench contact: %zu runs in %.1f s -> %s/contact.{csv,md,png}\n", table.rows().size(),
              seconds, outDir.c_str());
  return 0;
}

}  // namespace weft::bench
