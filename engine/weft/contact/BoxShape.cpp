#include <weft/contact/BoxShape.h>

namespace weft {

void BoxShape::sampleFace(const Vec3& p, const Vec3& local, int axis, double side,
                          SurfaceSample& out) const {
  out.distance = side * local[axis] - half_[axis];  // <= 0 inside
  out.normal = side * rotation_.col(axis);
  out.point = p - out.distance * out.normal;
}

bool BoxShape::sample(const Vec3& p, double reach, SurfaceSample& out) const {
  const Vec3 local = rotation_.transpose() * (p - center_);
  const Vec3 excess = local.cwiseAbs() - half_;  // per axis: > 0 outside that slab
  if (excess.maxCoeff() > 0.0) {
    // Outside: the distance gradient points from the nearest face, edge or corner; it is
    // continuous across the regions (the normal turns smoothly around edges and corners).
    const Vec3 outside = excess.cwiseMax(0.0).cwiseProduct(local.cwiseSign());
    const double distance = outside.norm();
    if (distance > reach) return false;
    out.distance = distance;
    out.normal = rotation_ * (outside / distance);
    out.point = p - distance * out.normal;
    return true;
  }
  // Inside: the nearest face.
  int axis = 0;
  excess.maxCoeff(&axis);
  sampleFace(p, local, axis, local[axis] >= 0.0 ? 1.0 : -1.0, out);
  return true;
}

// The entry face. The contact normal of a node inside the box is the normal of the face the node
// crossed to get there: the node's relative path runs from `from` (its start-of-step position,
// outside) to p (inside), and since the box is convex the segment crosses the surface exactly
// once, on the slab it enters last (the slab-clipping test of a ray against a box: along the
// segment, the slab of axis k, on the side the segment comes from, is entered at
// t_k = (s_k from_k - h_k) / (s_k from_k - s_k p_k); the entry point is at the largest t_k).
// Pushing the node back out through that face, by the depth below it, undoes the relative
// motion that put it inside, whatever the other faces' distances; the nearest face need not be
// the one it came through (the bottom of a box flush with the floor, 1 mm under a node lying
// there). The rule only concerns points inside the box, where the nearest-face normal was
// already piecewise constant: outside, and so for every node resting in the skin, the normal is
// still the smooth distance gradient. A node already inside at the start of the step (a scene
// that starts interpenetrating, or an unconverged step) has no entry face and keeps the nearest
// one. The frame is still a function of the sample point for a fixed start (the face is
// constant away from the switching boundaries and the point is p's projection onto it), which
// is how the backward pass differentiates it.
bool BoxShape::sampleMoved(const Vec3& p, const Vec3& from, double reach,
                           SurfaceSample& out) const {
  const Vec3 local = rotation_.transpose() * (p - center_);
  const Vec3 start = rotation_.transpose() * (from - center_);
  if ((local.cwiseAbs() - half_).maxCoeff() > 0.0 || (start.cwiseAbs() - half_).maxCoeff() <= 0.0)
    return sample(p, reach, out);
  int entry = -1;
  double entrySide = 1.0, latest = -1.0;
  for (int k = 0; k < 3; ++k) {
    const double side = start[k] >= 0.0 ? 1.0 : -1.0;
    const double above = side * start[k] - half_[k];  // > 0: the start is outside slab k
    if (above <= 0.0) continue;
    const double t = above / (side * start[k] - side * local[k]);  // denominator >= above > 0
    if (t > latest) latest = t, entry = k, entrySide = side;
  }
  sampleFace(p, local, entry, entrySide, out);
  return true;
}

}  // namespace weft
