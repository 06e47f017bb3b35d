#pragma once
// A solid capped cylinder of `radius` around the segment a-b (flat end caps).
//
// Outside, the normal is the signed distance's gradient (smooth around the rims). Inside, the
// gradient is the nearest surface's normal, which for a node the cylinder moved onto is the wrong
// one when a flat cap lies flush with a floor (a cylinder standing on the floor, or lying on it
// with a cap as a wall): a node on the floor that the side sweeps over stays nearer the bottom
// cap, whose normal would press it into the floor. sampleMoved gives such a point the surface
// (side or cap) its relative path crossed, as BoxShape does for faces.

#include <weft/contact/ObstacleShape.h>

namespace weft {

class CylinderShape final : public ObstacleShape {
 public:
  CylinderShape(const Vec3& a, const Vec3& b, double radius);
  const char* name() const override { return "cylinder"; }
  bool sample(const Vec3& p, double reach, SurfaceSample& out) const override;
  // Inside, having come from `from` outside: the side or the cap the segment from -> p entered
  // through (the distance is the depth below it). Otherwise as sample(p).
  bool sampleMoved(const Vec3& p, const Vec3& from, double reach,
                   SurfaceSample& out) const override;

 private:
  Vec3 middle_, axis_;  // axis_: unit, a -> b
  double halfLength_, radius_;
  Vec3 fallbackRadial_;  // a unit vector orthogonal to the axis, for points on the axis
};

}  // namespace weft
