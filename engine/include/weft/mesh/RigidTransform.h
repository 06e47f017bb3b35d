#pragma once
#include <weft/core/Types.h>

namespace weft {

// The scene contract's `transform`: rotate by rotate_deg about X, then Y, then Z, then translate.
struct RigidTransform {
  Vec3 rotateDeg = Vec3::Zero();
  Vec3 translate = Vec3::Zero();

  Mat3 rotation() const;
  Vec3 apply(const Vec3& p) const { return rotation() * p + translate; }
  void applyTo(NodeMatrix& points) const;
};

}  // namespace weft
