#include <weft/contact/ObstacleContactDetector.h>

#include <omp.h>

#include <algorithm>
#include <cmath>

namespace weft {
namespace {

constexpr int kMaxPathSegments = 16;

}  // namespace

void ObstacleContactDetector::detect(const NodeMatrix& x, const NodeMatrix& displacement, double h,
                                     std::vector<ContactPoint>& out) {
  const int m = static_cast<int>(x.rows());
  const int obstacleCount = static_cast<int>(obstacles_.size());
  const std::size_t first = out.size();
  collector_.collect(m, out, [&](int i, std::vector<ContactPoint>& local) {
    const Vec3 start = x.row(i);
    const Vec3 path = displacement.row(i);
    // Start, middle and end (DiffCloth); finer when the path is long against the margin, so a
    // fast node cannot step over a thin part of an obstacle's contact zone.
    const int segments =
        std::clamp(static_cast<int>(std::ceil(path.norm() / margin_)), 2, kMaxPathSegments);
    for (int o = 0; o < obstacleCount; ++o) {
      const ContactObstacle& obstacle = obstacles_[o];
      const double reach = obstacle.thickness() + margin_;
      SurfaceSample s;
      bool hit = false;
      int k = 0;
      for (; k <= segments && !hit; ++k)
        hit = obstacle.sample(start + (double(k) / segments) * path, start, reach, s) &&
              s.distance < reach;
      if (!hit) continue;
      const double fraction = double(k - 1) / segments;
      ContactPoint c;
      c.node = i;
      c.obstacle = o;
      c.normal = s.normal;
      c.friction = obstacle.friction();
      // Gap of the node's start to the end-of-step tangent plane, less the skin (see
      // ContactPoint.h); the surface's own velocity enters tangentially only.
      const double gap = s.normal.dot(start - s.point) - obstacle.thickness();
      const Vec3 surface = obstacle.surfaceVelocity(s.point);
      c.reference = surface - s.normal.dot(surface) * s.normal - (gap / h) * s.normal;
      c.sample = start + fraction * path;
      c.pathFraction = fraction;
      local.push_back(c);
    }
  });
  // The contacts are already in node order when the runtime hands out the static blocks in
  // thread order (as GCC's does); make the order independent of that.
  auto byNode = [](const ContactPoint& a, const ContactPoint& b) {
    return a.node != b.node ? a.node < b.node : a.obstacle < b.obstacle;
  };
  if (!std::is_sorted(out.begin() + first, out.end(), byNode))
    std::sort(out.begin() + first, out.end(), byNode);
}

}  // namespace weft
