#include <weft/contact/ContactLawJacobian.h>

namespace weft {

ContactLawJacobian differentiateSignoriniCoulomb(ContactBranch branch, const Vec3& normal,
                                                 double friction, const Vec3& free) {
  ContactLawJacobian j;
  if (branch == ContactBranch::Stick) {
    j.velocity = -Mat3::Identity();
    return j;
  }
  if (branch != ContactBranch::Slip) return j;  // take-off (or none): no impulse, nothing moves it
  const double wN = normal.dot(free);
  const Vec3 tangential = free - wN * normal;
  const double slide = tangential.norm();
  const Mat3 nn = normal * normal.transpose();
  // d(-w_N n)/dn = -(n w^T + w_N I), which is also d w_T / d n.
  const Mat3 tangentialByNormal = -(normal * free.transpose() + wN * Mat3::Identity());
  j.velocity = -nn;
  j.normal = tangentialByNormal;
  // Slip implies |w_T| > mu |w_N| >= 0, so t is defined; with mu = 0 only d du/dmu remains.
  if (slide == 0.0) return j;
  const Vec3 t = tangential / slide;
  j.friction = wN * t;
  if (friction == 0.0) return j;
  const Mat3 acrossSlide =
      Mat3::Identity() - t * t.transpose();  // (I - t t^T), d t / d w_T * |w_T|
  j.velocity += friction * (t * normal.transpose() + (wN / slide) * (acrossSlide - nn));
  // d t / d n = (I - t t^T) (d w_T / d n) / |w_T|.
  j.normal += friction * (t * free.transpose() + (wN / slide) * acrossSlide * tangentialByNormal);
  return j;
}

}  // namespace weft
