#include <weft/physics/WindForce.h>

#include <cmath>

namespace weft {

double WindForce::timeFactor(double t) const {
  if (wind_.constant) return 1.0;
  return 0.5 * (std::sin(2.0 * M_PI * wind_.frequency * t + wind_.phase) + 1.0);
}

}  // namespace weft
