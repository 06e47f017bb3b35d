// _weft.Simulator: the engine's Simulator stepped from Python, one step per call, so that a script
// can look at (or act on) the state between steps. The state is returned as copies.

#include "Bindings.h"
#include "NumpyArrays.h"
#include "SceneSource.h"
#include "StepStatsTable.h"

#include <weft/physics/Simulator.h>

#include <pybind11/stl.h>

#include <memory>

namespace weft::python {

namespace py = pybind11;

void bindSimulator(py::module_& m) {
  py::class_<Simulator>(m, "Simulator",
                        "The forward simulator of one scene, stepped one step at a time.")
      .def(py::init([](std::optional<std::string> file, std::optional<std::string> document,
                       std::vector<std::string> overrides) {
             const SceneSource source{std::move(file), std::move(document), std::move(overrides)};
             py::gil_scoped_release released;
             return std::make_unique<Simulator>(source.load());
           }),
           py::arg("file"), py::arg("document"), py::arg("overrides"))
      .def(
          "step",
          [](Simulator& sim) {
            StepStats stats;
            {
              py::gil_scoped_release released;
              stats = sim.step();
            }
            return stepStatsDict(stats);
          },
          "Advances one step; returns its statistics.")
      .def_property_readonly(
          "positions", [](const Simulator& sim) { return nodeArray(sim.positions()); },
          "The current positions, a [vertices, 3] copy.")
      .def_property_readonly(
          "velocities", [](const Simulator& sim) { return nodeArray(sim.velocities()); },
          "The current velocities, a [vertices, 3] copy.")
      .def_property_readonly("step_index", &Simulator::stepIndex,
                             "The index of the current state (0 before the first step).")
      .def_property_readonly("time", &Simulator::time, "The current time (s).")
      .def_property_readonly("dt", &Simulator::dt, "The scene's time step (s).")
      .def_property_readonly(
          "vertices", [](const Simulator& sim) { return sim.cloth().nodeCount(); },
          "The number of cloth vertices.")
      .def_property_readonly(
          "steps", [](const Simulator& sim) { return sim.scene().time.steps; },
          "The scene's time.steps.");
}

}  // namespace weft::python
