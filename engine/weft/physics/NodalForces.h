#pragma once
#include <weft/physics/ExternalForce.h>

#include <vector>

namespace weft {

// Constant forces on chosen nodes (the scene's per-cloth "forces"; DiffCloth's Flying Napkin).
class NodalForces final : public ExternalForce {
 public:
  explicit NodalForces(NodeMatrix forces) : forces_(std::move(forces)) {}
  const char* name() const override { return "external_forces"; }
  void accumulate(double, NodeMatrix& f) const override { f += forces_; }
  const NodeMatrix& forces() const { return forces_; }

 private:
  NodeMatrix forces_;  // m x 3, zero where no force is applied
};

}  // namespace weft
