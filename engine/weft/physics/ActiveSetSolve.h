#pragma once
// solver.contact = "active_set" (experimental): Newton-PCG on g (DiffCloth Eq. 3) with the
// step's contacts as an active set of linear constraints (ActiveContactSet.h): feasible
// iterates, multipliers as contact impulses, branch updates by Eq. 8, slip friction lagged. No
// contact ends a step on the wrong side of its constraint, whatever the iteration count; the
// lagged friction and branch cycling still make many steps reach the iteration cap. Steps with
// no contact are plain Newton-PCG (whatever solver.method says).

#include <weft/physics/StepSolver.h>

namespace weft {

class ActiveSetSolve final : public StepSolver {
 public:
  void prepareContacts(StepContext& ctx) override;
  void solve(StepContext& ctx) override;
  void record(const StepContext& ctx, StepContacts& out) const override;
};

}  // namespace weft
