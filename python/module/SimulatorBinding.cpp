// _weft.Simulator: the engine's Simulator stepped from Python, one step per call, so that a script
// can look at (or act on) the state between steps. The state is returned as copies. Every state
// is recorded (a Trajectory), so that backward_step can run the backward pass of any step taken
// (diff/StepBackward.h): what training a policy that acts between steps needs (DiffCloth
// Sec. 6.5).

#include "Bindings.h"
#include "NumpyArrays.h"
#include "SceneSource.h"
#include "StepStatsTable.h"

#include <weft/core/Error.h>
#include <weft/diff/ParameterSet.h>
#include <weft/diff/StepBackward.h>
#include <weft/physics/Simulator.h>
#include <weft/record/Trajectory.h>

#include <pybind11/stl.h>

#include <memory>

namespace weft::python {

namespace py = pybind11;

namespace {

// The simulator and the run it has recorded; the step-level backward pass over that run, made
// when first asked for (and again for other parameters or after more steps).
struct SteppedRun {
  std::unique_ptr<Simulator> sim;
  Trajectory trajectory;
  std::vector<std::string> backwardPaths;
  std::unique_ptr<ParameterSet> parameters;
  std::unique_ptr<StepBackward> backward;
  int backwardSteps = -1;  // the trajectory's step count when `backward` was made
};

NodeMatrix toNodeMatrix(const py::array_t<double, py::array::c_style | py::array::forcecast>& a,
                        int vertices, const char* name) {
  if (a.ndim() != 2 || a.shape(0) != vertices || a.shape(1) != 3)
    throw InputError("backward_step", name,
                     "expects a [" + std::to_string(vertices) + ", 3] array");
  NodeMatrix x(vertices, 3);
  const auto r = a.unchecked<2>();
  for (int i = 0; i < vertices; ++i)
    for (int c = 0; c < 3; ++c) x(i, c) = r(i, c);
  if (!x.allFinite()) throw InputError("backward_step", name, "is not finite");
  return x;
}

py::dict backwardStep(SteppedRun& run, int n,
                      const py::array_t<double, py::array::c_style | py::array::forcecast>& dx,
                      const py::array_t<double, py::array::c_style | py::array::forcecast>& dv,
                      const std::vector<std::string>& paths) {
  const int steps = run.trajectory.stepCount();
  if (n < 0 || n >= steps)
    throw InputError(
        "backward_step", "step",
        "must name a step taken, 0.." + std::to_string(steps - 1) + ", got " + std::to_string(n));
  const int m = run.sim->cloth().nodeCount();
  const NodeMatrix dLdx1 = toNodeMatrix(dx, m, "dL_dx"), dLdv1 = toNodeMatrix(dv, m, "dL_dv");
  NodeMatrix dLdx0 = NodeMatrix::Zero(m, 3), dLdv0(m, 3);
  Eigen::VectorXd gradient;
  {
    py::gil_scoped_release released;
    if (!run.backward || run.backwardPaths != paths || run.backwardSteps != steps) {
      run.backward.reset();
      run.parameters =
          std::make_unique<ParameterSet>(ParameterSet::fromPaths(run.sim->scene(), paths));
      // Each step's adjoint solved by the direct LU: a step's product exact to round-off.
      BackwardSettings settings = run.sim->scene().solver.backward;
      settings.method = "direct";
      run.backward = std::make_unique<StepBackward>(run.trajectory, *run.parameters, settings);
      run.backwardPaths = paths;
      run.backwardSteps = steps;
    }
    gradient = Eigen::VectorXd::Zero(run.parameters->size());
    run.backward->step(n, dLdx1, dLdv1, dLdx0, dLdv0, gradient);
    if (n == 0) run.backward->addInitial(dLdv0, gradient);
  }
  py::dict params;
  for (int k = 0; k < run.parameters->size(); ++k)
    params[py::str((*run.parameters)[k].path)] = gradient[k];
  py::dict out;
  out["dL_dx"] = nodeArray(dLdx0);
  out["dL_dv"] = nodeArray(dLdv0);
  out["dL_dparams"] = params;
  return out;
}

}  // namespace

void bindSimulator(py::module_& m) {
  py::class_<SteppedRun>(m, "Simulator",
                         "The forward simulator of one scene, stepped one step at a time.")
      .def(py::init([](std::optional<std::string> file, std::optional<std::string> document,
                       std::vector<std::string> overrides) {
             const SceneSource source{std::move(file), std::move(document), std::move(overrides)};
             py::gil_scoped_release released;
             auto run = std::make_unique<SteppedRun>();
             run->sim = std::make_unique<Simulator>(source.load());
             return run;
           }),
           py::arg("file"), py::arg("document"), py::arg("overrides"))
      .def(
          "step",
          [](SteppedRun& run) {
            StepStats stats;
            {
              py::gil_scoped_release released;
              run.sim->run(1, run.trajectory);
              stats = run.trajectory.steps.back();
            }
            return stepStatsDict(stats);
          },
          "Advances one step; returns its statistics.")
      .def("backward_step", &backwardStep, py::arg("step"), py::arg("dL_dx"), py::arg("dL_dv"),
           py::arg("params"),
           "The backward pass of step `step` (state step -> step + 1) of the run so far.")
      .def_property_readonly(
          "positions", [](const SteppedRun& r) { return nodeArray(r.sim->positions()); },
          "The current positions, a [vertices, 3] copy.")
      .def_property_readonly(
          "velocities", [](const SteppedRun& r) { return nodeArray(r.sim->velocities()); },
          "The current velocities, a [vertices, 3] copy.")
      .def_property_readonly(
          "step_index", [](const SteppedRun& r) { return r.sim->stepIndex(); },
          "The index of the current state (0 before the first step).")
      .def_property_readonly(
          "time", [](const SteppedRun& r) { return r.sim->time(); }, "The current time (s).")
      .def_property_readonly(
          "dt", [](const SteppedRun& r) { return r.sim->dt(); }, "The scene's time step (s).")
      .def_property_readonly(
          "vertices", [](const SteppedRun& r) { return r.sim->cloth().nodeCount(); },
          "The number of cloth vertices.")
      .def_property_readonly(
          "steps", [](const SteppedRun& r) { return r.sim->scene().time.steps; },
          "The scene's time.steps.");
}

}  // namespace weft::python
