#pragma once
// The box as the evolution strategies (CMA-ES, (1+1)-ES) search it: coordinates centred on the
// starting point and divided by each variable's box width, so that one step size fits every
// variable (Hansen's tutorial asks for variables scaled so that "a single standard deviation on
// all variables is useful"), and the repair that keeps every evaluated point inside the box.
//
// Scale: u = (z - z0) / w with w the width upper - lower of the variable's box, capped at
// kMaxWidth optimiser units. The cap stands in for the box of variables that are open (forces,
// wind direction) or whose default box spans decades (stretch, 1e-3..1e9 N/m): ParameterSpace
// coordinates are log(value) for stiffness and density, value / |starting value| otherwise, so 2
// units is a factor e^2 or twice the starting magnitude (a handle knot with a task box: the
// whole box, ParameterSpace.h). The initial step size of both methods
// is kInitialStepFraction of that width: a quarter of the box (pycma's advice for sigma0 on a
// bounded domain), so that start +- 2 sigma spans it.
//
// Repair: projection, the nearest point of the box (each coordinate clipped to its bounds). The
// repaired point is the one evaluated and logged, and the one the method then uses in its update
// ("Lamarckian" repair, Hansen's tutorial, Appendix B on boundaries; compared with the
// alternatives by Biedrzycki 2019, "Handling bound constraints in CMA-ES: an experimental study",
// Swarm and Evolutionary Computation 52): the mean stays inside the box and a minimum on the
// boundary is reached exactly, without a penalty weight to tune against the loss's scale.

#include <Eigen/Core>

namespace weft {

class SearchBox {
 public:
  static constexpr double kMaxWidth = 2.0;
  static constexpr double kInitialStepFraction = 0.25;

  // `start` must lie in [lower, upper]; infinite bounds are allowed.
  SearchBox(const Eigen::VectorXd& start, const Eigen::VectorXd& lower,
            const Eigen::VectorXd& upper);

  int size() const { return static_cast<int>(start_.size()); }
  // The repaired point of search point u, in optimiser coordinates: inside [lower, upper] to the
  // last bit (the projection is done after the change of coordinates, so rounding cannot leave
  // the box).
  Eigen::VectorXd repairedCoordinates(const Eigen::VectorXd& u) const;
  // Search coordinates of optimiser coordinates z.
  Eigen::VectorXd toSearch(const Eigen::VectorXd& z) const;
  const Eigen::VectorXd& widths() const { return width_; }

 private:
  Eigen::VectorXd start_, lower_, upper_, width_;
};

}  // namespace weft
