#pragma once
// The coordinates an optimiser works in for a scene's parameters, and their bounds.
//
// Bounds: each parameter kind has a default box (stiffness and density strictly positive, a
// wind strength within the loader's range, angles and vectors free), replaced by the task's
// explicit task.bounds entry when there is one. The scene's starting value must lie inside.
//
// Coordinates: the physical values span decades (a stretch of 400 N/m next to a wind direction
// component of 0.2), while L-BFGS-B's first step and Adam's learning rate are in the units of the
// variables. So strictly positive material parameters (stretch, bend, density) are optimised as
// log(value) (SceneParameter::logScale), and every other parameter as value / s with s its
// starting magnitude (1 when it starts at 0), except a handle's spline knots and keyframe offsets
// and tangents (HandleOffset, HandleTangent) with a finite task.bounds box: their s is half its
// width, so the box spans 2 units whatever the start.
//
// Why the handles differ: a knot's components are the coordinates of a path, and one's size says
// nothing about how far it, or another, may move; scaled by their starts, knots starting near 0
// would take steps far smaller than their box. A material constant's or the wind's magnitude is
// a scale, and there the box is not better (docs/how-it-works/optimisers.md, "Parameter
// scaling").
//
// Gradients follow by the chain rule: dL/dz = dL/dtheta * dtheta/dz, with dtheta/dz = theta (log)
// or s (linear).
//
// The start maps back exactly: exp(log(v)) is not always v, and a scene whose forward solve stops
// unconverged on some steps moves under such a last-bit change. So a
// coordinate equal to the start's is mapped to the scene's own value, and an optimiser's first
// evaluation is the run `weft simulate` makes of the scene as written.

#include <weft/diff/ParameterSet.h>

#include <Eigen/Core>

#include <vector>

namespace weft {

class ParameterSpace {
 public:
  // Throws InputError (file, "task.bounds.<path>" or the parameter path) when the starting
  // value lies outside its bounds.
  ParameterSpace(const Scene& scene, const ParameterSet& parameters);

  int size() const { return static_cast<int>(parameters_.size()); }
  const std::vector<SceneParameter>& parameters() const { return parameters_; }

  Eigen::VectorXd toCoordinates(const Eigen::VectorXd& values) const;
  Eigen::VectorXd toValues(const Eigen::VectorXd& z) const;
  // dL/dz from dL/dtheta at z.
  Eigen::VectorXd gradientToCoordinates(const Eigen::VectorXd& z,
                                        const Eigen::VectorXd& dLdtheta) const;
  // dL/dtheta from dL/dz at z.
  Eigen::VectorXd gradientToValues(const Eigen::VectorXd& z, const Eigen::VectorXd& dLdz) const;

  Eigen::VectorXd lowerValues() const;
  Eigen::VectorXd upperValues() const;
  Eigen::VectorXd lowerCoordinates() const { return toCoordinates(lowerValues()); }
  Eigen::VectorXd upperCoordinates() const { return toCoordinates(upperValues()); }
  const Eigen::VectorXd& initialValues() const { return initial_; }
  // s of a linear coordinate (value = z * s); unused for a log-scaled one.
  double linearScale(int i) const { return scale_[i]; }

 private:
  std::vector<SceneParameter> parameters_;  // with lower, upper and logScale set
  Eigen::VectorXd initial_, initialCoordinates_, scale_;
};

// The default box and log-scale choice of a parameter kind (written into `parameter`).
void applyDefaultBounds(SceneParameter& parameter);

}  // namespace weft
