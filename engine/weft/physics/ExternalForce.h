#pragma once
// An external force effect (gravity, wind, per-node forces): adds its nodal forces (N) at a
// given time. Each exists only when the scene names its effect.

#include <weft/core/Types.h>

namespace weft {

class ExternalForce {
 public:
  virtual ~ExternalForce() = default;
  virtual const char* name() const = 0;
  virtual void accumulate(double time, NodeMatrix& forces) const = 0;
};

}  // namespace weft
