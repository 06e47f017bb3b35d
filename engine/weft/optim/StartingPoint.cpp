#include <weft/contact/HandleObstacleCheck.h>
#include <weft/optim/SearchBox.h>
#include <weft/optim/StartingPoint.h>

#include <random>

namespace weft {

StartingPoint drawStartingPoint(const Scene& scene, const ParameterSet& parameters,
                                const ParameterSpace& space, unsigned seed) {
  const Eigen::VectorXd z0 = space.toCoordinates(space.initialValues());
  const SearchBox box(z0, space.lowerCoordinates(), space.upperCoordinates());
  std::seed_seq sequence{seed, 0x5eedu};
  std::mt19937_64 random(sequence);
  std::uniform_real_distribution<double> uniform(-0.25, 0.25);
  const auto draw = [&]() {
    Eigen::VectorXd u(z0.size());
    for (int i = 0; i < u.size(); ++i) u[i] = uniform(random);
    return box.repairedCoordinates(u);
  };
  const auto inside = [&](const Eigen::VectorXd& z) {
    return !handlesEnteringObstacles(parameters.withValues(scene, space.toValues(z))).empty();
  };

  StartingPoint start;
  start.coordinates = draw();
  // (No handle or no obstacle: handlesEnteringObstacles returns at once, and this is the draw.)
  if (!inside(start.coordinates)) return start;
  // Nothing to keep out when the scene's own handles already enter an obstacle: its author's
  // choice, and the draws around it may all do so. (z0 maps back to the scene's own values
  // exactly: ParameterSpace.h.)
  if (!handlesEnteringObstacles(scene).empty()) {
    start.handlesOutsideObstacles = false;
    return start;
  }
  for (int n = 2; n <= kMaxStartingPointDraws; ++n) {
    Eigen::VectorXd z = draw();
    if (inside(z)) continue;
    start.coordinates = std::move(z);
    start.draws = n;
    return start;
  }
  start.handlesOutsideObstacles = false;
  start.draws = kMaxStartingPointDraws;
  return start;
}

}  // namespace weft
