#pragma once
// The local Signorini-Coulomb law of one contact (DiffCloth Eq. 8, solved per node as in Ly et
// al. 2020 and DiffCloth Eq. 12). Everything is in velocities: `free` is the contact velocity
// the node would have without this contact's impulse, and the law picks the velocity change
// du (impulse = effective mass * du) of exactly one branch:
//   take-off  free_N >= 0                       du = 0            (u = free, u_N >= 0)
//   stick     |free_T| <= mu |free_N|           du = -free        (u = 0, |r_T| <= mu r_N)
//   slip      otherwise                         du = -free_N n - mu |free_N| t   (u_N = 0,
//             t = free_T / |free_T|; r_T = -mu r_N t sits on the cone, opposite to u_T)
// The stick test uses <=, so |free_T| = 0 (including mu = 0 with no tangential motion) is a
// stick with zero friction, never a division by zero (notes Sec. 5, pitfall 4).

#include <weft/record/ContactPoint.h>

namespace weft {

ContactBranch solveSignoriniCoulomb(const Vec3& normal, double friction, const Vec3& free,
                                    Vec3& velocityChange);

}  // namespace weft
