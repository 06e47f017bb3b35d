#pragma once
// One term of a task loss: a function of the recorded positions x_0..x_N. The adjoint needs its
// value and its partial derivatives dL/dx_n per state (the right-hand sides of DiffCloth
// Eqs. 16 and 19).

#include <weft/core/Types.h>
#include <weft/record/Trajectory.h>

#include <vector>

namespace weft {

class LossTerm {
 public:
  virtual ~LossTerm() = default;
  virtual const char* name() const = 0;
  virtual double value(const Trajectory& trajectory) const = 0;
  // gradient[n] += dL/dx_n for every state n (gradient has one m x 3 matrix per state).
  virtual void addGradient(const Trajectory& trajectory,
                           std::vector<NodeMatrix>& gradient) const = 0;
};

}  // namespace weft
