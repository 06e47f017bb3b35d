#pragma once
// The task loss's gradient exactly as an optimiser gets it (`weft gradient`): the scene's own
// forward solver, its own backward settings, error-controlled to solver.backward.accuracy
// (GradientErrorControl.h), at the scene's parameter values.

#include <weft/diff/Backpropagation.h>
#include <weft/diff/ParameterSet.h>
#include <weft/scene/Scene.h>

namespace weft {

struct SceneGradient {
  Eigen::VectorXd values;    // the parameters' values, in the ParameterSet's order
  GradientResult result;     // loss, dL/dtheta, its error estimate, the backward statistics
  int unconvergedSteps = 0;  // of the forward run
  double forwardSeconds = 0.0;
};

// Throws InputError for a scene without a task.
SceneGradient sceneGradient(const Scene& scene, const ParameterSet& parameters);

}  // namespace weft
