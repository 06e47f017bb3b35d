#pragma once
// solver.method = "pd" without contact: local-global Projective Dynamics iterations (DiffCloth
// Sec. 3.1, Eqs. 6-7), with Anderson acceleration (Peng et al. 2018) and an energy safeguard
// unless solver.acceleration is "none".

#include <weft/physics/AndersonAccelerator.h>
#include <weft/physics/StepSolver.h>

namespace weft {

class ProjectiveDynamicsSolve final : public StepSolver {
 public:
  explicit ProjectiveDynamicsSolve(const StepContext& ctx);
  void solve(StepContext& ctx) override;

 private:
  AndersonAccelerator anderson_;
};

}  // namespace weft
