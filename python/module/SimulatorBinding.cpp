// _weft.Simulator: the engine's Simulator stepped from Python, one step per call, so that a script
// can look at (or act on) the state between steps: drive the handles (a policy's action) or set
// the state. The state is returned as copies. Every state is recorded (a Trajectory), so that
// backward_step can run the backward pass of any step taken (diff/StepBackward.h), with the
// gradient of the handles' driven offsets: what training a policy that acts between steps needs
// (DiffCloth Sec. 6.5, Fig. 13).

#include "Bindings.h"
#include "NumpyArrays.h"
#include "SceneSource.h"
#include "StepStatsTable.h"

#include <weft/core/Error.h>
#include <weft/diff/ParameterSet.h>
#include <weft/diff/StepBackward.h>
#include <weft/physics/Model.h>
#include <weft/physics/Simulator.h>
#include <weft/record/StepContacts.h>
#include <weft/record/Trajectory.h>

#include <pybind11/stl.h>

#include <cstdint>
#include <memory>
#include <vector>

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
  int backwardSteps = -1;    // the trajectory's step count when `backward` was made
  std::vector<char> driven;  // per handle: driven from Python (drive_handles) at least once
  int stateSetAt = 0;        // the last state set from Python (set_state); 0 if none
};

using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

NodeMatrix toNodeMatrix(const DoubleArray& a, int vertices, const char* name,
                        const char* call = "backward_step") {
  if (a.ndim() != 2 || a.shape(0) != vertices || a.shape(1) != 3)
    throw InputError(call, name, "expects a [" + std::to_string(vertices) + ", 3] array");
  NodeMatrix x(vertices, 3);
  const auto r = a.unchecked<2>();
  for (int i = 0; i < vertices; ++i)
    for (int c = 0; c < 3; ++c) x(i, c) = r(i, c);
  if (!x.allFinite()) throw InputError(call, name, "is not finite");
  return x;
}

// A parameter whose partials read a driven handle's trajectory or target (ParameterPartials),
// which the driven run no longer follows.
void refuseDrivenHandleParameters(const SteppedRun& run, const ParameterSet& parameters) {
  const std::vector<HandleGroup>& handles = run.sim->model().handles();
  for (const SceneParameter& p : parameters.parameters()) {
    using Kind = SceneParameter::Kind;
    if (p.kind != Kind::HandleOffset && p.kind != Kind::HandleTangent &&
        p.kind != Kind::AttachmentStiffness)
      continue;
    for (std::size_t g = 0; g < handles.size(); ++g)
      if (run.driven[g] && handles[g].cloth == p.cloth && handles[g].attachment == p.index)
        throw InputError("backward_step", p.path,
                         "is a parameter of handle " + std::to_string(g) +
                             ", which is driven from Python; its gradient is dL_dhandles");
  }
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
  if (n < run.stateSetAt)
    throw InputError("backward_step", "step",
                     "the state was set from Python at step " + std::to_string(run.stateSetAt) +
                         "; the steps before it are not part of this run's backward pass, got " +
                         std::to_string(n));
  const int m = run.sim->cloth().nodeCount();
  const NodeMatrix dLdx1 = toNodeMatrix(dx, m, "dL_dx"), dLdv1 = toNodeMatrix(dv, m, "dL_dv");
  NodeMatrix dLdx0 = NodeMatrix::Zero(m, 3), dLdv0(m, 3);
  NodeMatrix dLdHandles =
      NodeMatrix::Zero(static_cast<Eigen::Index>(run.sim->model().handles().size()), 3);
  Eigen::VectorXd gradient;
  {
    py::gil_scoped_release released;
    if (!run.backward || run.backwardPaths != paths || run.backwardSteps != steps) {
      run.backward.reset();
      run.parameters =
          std::make_unique<ParameterSet>(ParameterSet::fromPaths(run.sim->scene(), paths));
      refuseDrivenHandleParameters(run, *run.parameters);
      // Each step's adjoint solved by the direct LU: a step's product exact to round-off.
      BackwardSettings settings = run.sim->scene().solver.backward;
      settings.method = "direct";
      run.backward = std::make_unique<StepBackward>(run.trajectory, *run.parameters, settings);
      run.backwardPaths = paths;
      run.backwardSteps = steps;
    }
    gradient = Eigen::VectorXd::Zero(run.parameters->size());
    run.backward->step(n, dLdx1, dLdv1, dLdx0, dLdv0, gradient, &dLdHandles);
    if (n == 0) run.backward->addInitial(dLdv0, gradient);
  }
  py::dict params;
  for (int k = 0; k < run.parameters->size(); ++k)
    params[py::str((*run.parameters)[k].path)] = gradient[k];
  py::dict out;
  out["dL_dx"] = nodeArray(dLdx0);
  out["dL_dv"] = nodeArray(dLdv0);
  out["dL_dparams"] = params;
  out["dL_dhandles"] = nodeArray(dLdHandles);
  return out;
}

void driveHandles(SteppedRun& run, const DoubleArray& offsets) {
  const int count = static_cast<int>(run.sim->model().handles().size());
  if (count == 0) throw InputError("drive_handles", "offsets", "the scene has no handles");
  const NodeMatrix o = toNodeMatrix(offsets, count, "offsets", "drive_handles");
  for (int g = 0; g < count; ++g) {
    run.sim->driveHandle(g, o.row(g).transpose());
    run.driven[static_cast<std::size_t>(g)] = 1;
  }
}

void setState(SteppedRun& run, const DoubleArray& x, const DoubleArray& v) {
  const int m = run.sim->cloth().nodeCount();
  const NodeMatrix xs = toNodeMatrix(x, m, "positions", "set_state");
  const NodeMatrix vs = toNodeMatrix(v, m, "velocities", "set_state");
  const int step = run.sim->stepIndex();
  run.sim->restart(step, xs, vs);
  if (!run.trajectory.positions.empty()) {
    // The recorded state `step` is now the one set: the steps after it start from it.
    run.trajectory.positions.back() = xs;
    run.trajectory.velocities.back() = vs;
  }
  run.stateSetAt = step;
  run.backward.reset();
}

// The last step's contacts (record/ContactPoint.h) as arrays, one row per contact.
py::dict contactArrays(const SteppedRun& run) {
  static const StepContacts none;
  const StepContacts& last =
      run.trajectory.contacts.empty() ? none : run.trajectory.contacts.back();
  const std::size_t k = last.points.size();
  std::vector<int> node(k), partner(k), obstacle(k);
  std::vector<std::uint8_t> branch(k);
  std::vector<double> friction(k);
  NodeMatrix normal(static_cast<Eigen::Index>(k), 3), impulse(static_cast<Eigen::Index>(k), 3),
      velocity(static_cast<Eigen::Index>(k), 3);
  for (std::size_t i = 0; i < k; ++i) {
    const ContactPoint& c = last.points[i];
    const auto r = static_cast<Eigen::Index>(i);
    node[i] = c.node;
    partner[i] = c.partner;
    obstacle[i] = c.obstacle;
    branch[i] = static_cast<std::uint8_t>(c.branch);
    friction[i] = c.friction;
    normal.row(r) = c.normal.transpose();
    impulse.row(r) = c.impulse.transpose();
    velocity.row(r) = c.velocity.transpose();
  }
  py::dict out;
  out["node"] = vectorArray(node);
  out["partner"] = vectorArray(partner);
  out["obstacle"] = vectorArray(obstacle);
  out["branch"] = vectorArray(branch);
  out["friction"] = vectorArray(friction);
  out["normal"] = nodeArray(normal);
  out["impulse"] = nodeArray(impulse);
  out["velocity"] = nodeArray(velocity);
  return out;
}

py::list handleList(const SteppedRun& run) {
  py::list out;
  const NodeMatrix& rest = run.sim->cloth().rest.vertices;
  for (const HandleGroup& g : run.sim->model().handles()) {
    NodeMatrix anchors(static_cast<Eigen::Index>(g.nodes.size()), 3);
    for (std::size_t k = 0; k < g.nodes.size(); ++k)
      anchors.row(static_cast<Eigen::Index>(k)) = rest.row(g.nodes[k]);
    py::dict h;
    h["cloth"] = g.cloth;
    h["attachment"] = g.attachment;
    h["vertices"] = vectorArray(g.nodes);
    h["anchors"] = nodeArray(anchors);
    h["stiffness"] = g.stiffness;
    out.append(h);
  }
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
             run->driven.assign(run->sim->model().handles().size(), 0);
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
      .def("drive_handles", &driveHandles, py::arg("offsets"),
           "Drives every handle to its anchors + offsets[h] from the next step on.")
      .def("set_state", &setState, py::arg("positions"), py::arg("velocities"),
           "Replaces the current state.")
      .def_property_readonly("contacts", &contactArrays,
                             "The last step's contacts as arrays, one row per contact.")
      .def_property_readonly(
          "handles", &handleList,
          "The scene's handles: cloth, attachment, vertices, anchors, stiffness.")
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
