// _weft.gradient: the adjoint gradient of the scene's task loss, as `weft gradcheck` computes it
// (tightAdjointGradient with gradcheck's default options: the tightened forward run and adjoint
// solves), without the finite differences. Its values are gradcheck's `adjoint` column.

#include "Bindings.h"
#include "NumpyArrays.h"
#include "SceneSource.h"
#include "WarningLines.h"

#include <weft/core/Error.h>
#include <weft/diff/GradientCheck.h>
#include <weft/diff/GradientErrorControl.h>
#include <weft/diff/ParameterSet.h>
#include <weft/record/ConvergenceReport.h>

#include <pybind11/stl.h>

#include <optional>

namespace weft::python {

namespace py = pybind11;

namespace {

// What the pass gives, computed without the GIL.
struct Gradient {
  std::vector<std::string> names;
  Eigen::VectorXd values;
  TightAdjointGradient tight;
  std::vector<std::string> warnings;
};

Gradient computeGradient(const SceneSource& source,
                         const std::optional<std::vector<std::string>>& paths,
                         const std::optional<std::vector<double>>& values) {
  Scene scene = source.load();
  // The checks and messages of `weft gradcheck` (GradcheckCommand.cpp).
  if (!scene.task)
    throw InputError(source.name(), "task",
                     "the scene has no task; gradcheck needs task.loss and parameters");
  const ParameterSet parameters =
      paths ? ParameterSet::fromPaths(scene, *paths) : ParameterSet::fromTask(scene);
  if (parameters.empty())
    throw InputError(source.name(), "task.parameters",
                     "no parameters to check: list them in task.parameters or give --param PATH");
  if (values) {
    if (static_cast<int>(values->size()) != parameters.size())
      throw InputError(source.name(), "values",
                       "expects " + std::to_string(parameters.size()) +
                           " values (one per parameter), got " + std::to_string(values->size()));
    scene = parameters.withValues(
        scene, Eigen::Map<const Eigen::VectorXd>(values->data(), parameters.size()));
  }
  Gradient out;
  for (const SceneParameter& p : parameters.parameters()) out.names.push_back(p.path);
  out.values = parameters.values(scene);
  out.tight = tightAdjointGradient(scene, parameters, GradientCheckOptions{});  // gradcheck's
  addWarningLines(gradientErrorWarning(out.tight.result.error), out.warnings);
  addWarningLines(unconvergedGradientWarning(out.tight.unconvergedSteps), out.warnings);
  return out;
}

std::vector<double> toVector(const Eigen::VectorXd& v) {
  return std::vector<double>(v.data(), v.data() + v.size());
}

py::dict gradient(const SceneSource& source, const std::optional<std::vector<std::string>>& paths,
                  const std::optional<std::vector<double>>& values) {
  std::optional<Gradient> g;
  {
    py::gil_scoped_release released;
    g = computeGradient(source, paths, values);
  }
  const TightAdjointGradient& tight = g->tight;
  const AdjointSolverStats& b = tight.result.solver;
  py::dict out;
  out["params"] = g->names;
  out["values"] = vectorArray(toVector(g->values));
  out["gradient"] = vectorArray(toVector(tight.result.gradient));
  out["loss"] = tight.result.loss;
  // The gradient's estimated relative error and each parameter's absolute one
  // (GradientErrorControl.h), as gradcheck reports them.
  const GradientErrorEstimate& e = tight.result.error;
  out["error_estimate"] = e.relative;
  out["error_estimates"] = vectorArray(toVector(e.absolute));
  out["error"] = py::dict(py::arg("basis") = e.basis, py::arg("passes") = e.passes,
                          py::arg("requested") = e.requested, py::arg("met") = e.met,
                          py::arg("tolerance") = e.tolerance);
  out["backward"] = py::dict(
      py::arg("method") = tight.backward.method, py::arg("tolerance") = tight.backward.tolerance,
      py::arg("solves") = b.solves, py::arg("iterations") = b.iterations,
      py::arg("max_iterations") = b.maxIterations, py::arg("not_converged") = b.notConverged,
      py::arg("fallbacks") = b.fallbacks, py::arg("adjoint_growth") = b.adjointGrowth);
  out["unconverged_steps"] = tight.unconvergedSteps;
  out["warnings"] = g->warnings;
  return out;
}

}  // namespace

void bindGradient(py::module_& m) {
  m.def(
      "gradient",
      [](std::optional<std::string> file, std::optional<std::string> document,
         std::vector<std::string> overrides, std::optional<std::vector<std::string>> params,
         std::optional<std::vector<double>> values) {
        return gradient({std::move(file), std::move(document), std::move(overrides)}, params,
                        values);
      },
      py::arg("file"), py::arg("document"), py::arg("overrides"), py::arg("params"),
      py::arg("values"),
      "The adjoint gradient of the task loss with respect to params (default: task.parameters), "
      "at values (default: the scene's), as `weft gradcheck` computes its adjoint.");
}

}  // namespace weft::python
