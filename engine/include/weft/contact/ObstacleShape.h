#pragma once
// The geometry of a rigid obstacle in its own (body) frame: a signed distance with an outward
// unit normal. Contact detection evaluates it at a few points of each node's path per step
// (DiffCloth's isInContact); the normal and closest point found there freeze the contact frame
// for the step (the explicit J_n of DiffCloth Eq. 9).

#include <weft/core/Types.h>

namespace weft {

struct SurfaceSample {
  double distance = 0.0;        // signed: negative inside the obstacle
  Vec3 normal = Vec3::UnitY();  // unit, pointing out of the obstacle
  Vec3 point = Vec3::Zero();    // closest surface point
};

class ObstacleShape {
 public:
  virtual ~ObstacleShape() = default;
  virtual const char* name() const = 0;
  // Fills `out` for the point p and returns true, unless the shape can tell cheaply that p is
  // more than `reach` outside it (then returns false and leaves `out` unspecified). Safe to call
  // concurrently.
  virtual bool sample(const Vec3& p, double reach, SurfaceSample& out) const = 0;
  // The same for a point that got to p by moving, relative to the shape, from `from` (both in
  // the body frame): contact detection's sample of a node's path, `from` being the node's
  // start-of-step position in the start-of-step body frame. Shapes whose inside normal is not
  // determined by p alone override it (BoxShape: the face the node came in through); the others
  // answer sample(p).
  virtual bool sampleMoved(const Vec3& p, const Vec3& from, double reach,
                           SurfaceSample& out) const {
    (void)from;
    return sample(p, reach, out);
  }
};

}  // namespace weft
