#pragma once
// A seed's starting point for a comparison of optimisers (DiffCloth Table 2: "All methods start
// the optimization with the same initial random seed set"): uniform within a quarter of each
// variable's box width (SearchBox's width, capped for open boxes) on either side of the scene's
// values, projected into the box, from its own random stream (the evolution strategies draw
// from theirs, seeded with the same s).
//
// Handles: a draw whose handle targets pass inside an obstacle is drawn again from the same
// stream. Such a start is not a trajectory anyone would begin from (the paper's starts are
// manipulator paths that pull the garment onto the body, Figs. 9-10), and it is not one the
// simulator can solve: the attachment's spring pulls cloth centimetres into the obstacle
// against the contact (HandleObstacleCheck.h), steps stop unconverged, and the loss around it
// jumps. Only the start is kept out; the optimisers may still search anywhere in the box. A
// draw accepted at once is the first draw of the stream, so tasks without handles or obstacles
// start at the first draw.

#include <weft/diff/ParameterSet.h>
#include <weft/optim/ParameterSpace.h>

#include <Eigen/Core>

namespace weft {

struct StartingPoint {
  Eigen::VectorXd coordinates;  // optimiser coordinates (ParameterSpace)
  int draws = 1;                // how many draws it took (1: the first)
  // False when none of kMaxStartingPointDraws draws kept the handles outside the obstacles, or
  // the scene's own values do not: the first draw is returned.
  bool handlesOutsideObstacles = true;
};

constexpr int kMaxStartingPointDraws = 10000;

StartingPoint drawStartingPoint(const Scene& scene, const ParameterSet& parameters,
                                const ParameterSpace& space, unsigned seed);

}  // namespace weft
