#include <weft/scene/ValueChecks.h>

namespace weft {

double readDensity(const JsonReader& r) {
  return r.positive();
}

double readStiffness(const JsonReader& r) {
  return r.number(0.0, kMaxStiffness);
}

double readAttachmentStiffness(const JsonReader& r) {
  const double k = r.positive();
  if (k > kMaxStiffness) r.fail("is unreasonably large");
  return k;
}

double readFriction(const JsonReader& r) {
  return r.number(0.0, 1e3);
}

double readWindStrength(const JsonReader& r) {
  return r.number(-1e6, 1e6);
}

double readWindFrequency(const JsonReader& r) {
  return r.number(0.0, 1e6);
}

double readWindPhase(const JsonReader& r) {
  return r.number(-1e6, 1e6);
}

Vec3 readWindDirection(const JsonReader& r) {
  const Vec3 d = r.vec3();
  if (!(d.norm() > 0.0)) r.fail("must be a nonzero vector");
  return d;
}

}  // namespace weft
