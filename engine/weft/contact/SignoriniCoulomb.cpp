#include <weft/contact/SignoriniCoulomb.h>

namespace weft {

ContactBranch solveSignoriniCoulomb(const Vec3& normal, double friction, const Vec3& free,
                                    Vec3& velocityChange) {
  const double freeNormal = normal.dot(free);
  if (freeNormal >= 0.0) {  // Eq. 8a: separating without help, no force
    velocityChange.setZero();
    return ContactBranch::TakeOff;
  }
  const Vec3 tangential = free - freeNormal * normal;
  const double slide = tangential.norm();
  const double cone = friction * -freeNormal;  // mu r_N / m
  if (slide <= cone) {                         // Eq. 8b: the cone holds the node
    velocityChange = -free;
    return ContactBranch::Stick;
  }
  // Eq. 8c: normal velocity cancelled, friction on the cone boundary against the slip.
  velocityChange = -freeNormal * normal - (cone / slide) * tangential;
  return ContactBranch::Slip;
}

}  // namespace weft
