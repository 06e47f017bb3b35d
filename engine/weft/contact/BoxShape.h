#pragma once
// A solid oriented box: centre, half extents, rotation (body axes in world columns).
//
// Outside the box the normal is the signed distance's gradient: it turns smoothly around edges
// and corners (a continuous frame, which is what lets a cloth slide over an edge and what the
// backward pass differentiates, DiffCloth Fig. 2). Inside, the distance's gradient is the
// nearest face's normal, which is not a contact normal a node should get when the box moved
// into it: a box standing on a floor has its bottom face flush with the floor, so a node lying
// on the floor that the box's side face sweeps over is nearer the bottom face (1 mm, its skin)
// than the side it came in through (however far the box moved), and the bottom normal would
// press it into the floor while the wall passes over it. sampleMoved therefore gives a point
// inside the box the face its relative path entered through (see BoxShape.cpp).

#include <weft/contact/ObstacleShape.h>

namespace weft {

class BoxShape final : public ObstacleShape {
 public:
  BoxShape(const Vec3& center, const Vec3& halfExtents, const Mat3& rotation)
      : center_(center), half_(halfExtents), rotation_(rotation) {}
  const char* name() const override { return "box"; }
  // Inside: the nearest face (the signed distance's gradient).
  bool sample(const Vec3& p, double reach, SurfaceSample& out) const override;
  // Inside, having come from `from` outside the box: the face the segment from -> p crosses
  // into the box (p is projected onto that face's plane, the distance is the depth below it).
  // Otherwise as sample(p).
  bool sampleMoved(const Vec3& p, const Vec3& from, double reach,
                   SurfaceSample& out) const override;

 private:
  // The face sample of a point inside the box: depth below face `axis` on side `side` (+1/-1).
  void sampleFace(const Vec3& p, const Vec3& local, int axis, double side,
                  SurfaceSample& out) const;
  Vec3 center_, half_;
  Mat3 rotation_;
};

}  // namespace weft
