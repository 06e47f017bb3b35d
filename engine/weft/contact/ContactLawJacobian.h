#pragma once
// The derivatives of one contact's Signorini-Coulomb law (DiffCloth Eq. 8; the forward closed
// form is engine/weft/contact/SignoriniCoulomb.h) within the branch it is in, as the backward
// pass needs them (DiffCloth Eqs. 26-27; notes Sec. 3.2), and the forward Newton contact solve
// with them (Simulator::solveContactNewton). The law maps the contact's free
// velocity w (what it would have without its own impulse) to the velocity change
// du = L(w; n, mu), impulse = effective mass * du:
//   take-off  du = 0                     all derivatives zero
//   stick     du = -w                    d du/dw = -I
//   slip      du = -w_N n + mu w_N t     (w_N = n.w < 0, t = w_T / |w_T|)
//             d du/dw  = -n n^T + mu t n^T + mu w_N (I - t t^T - n n^T) / |w_T|
//             d du/dn  = -(n w^T + w_N I) + mu t w^T - mu w_N (I - t t^T)(n w^T + w_N I) / |w_T|
//             d du/dmu = w_N t
// The paper's Eq. 27, dr/dv = -(dC/dr)^-1 dC/du J, cannot be used literally: dC/dr is singular
// for stick (C = u) and for slip (the u_N = 0 row has no r in it). Differentiating the closed
// form in the free velocity instead gives the same derivative of the step's solution, and every
// block is finite (notes Sec. 3.1).

#include <weft/record/ContactPoint.h>

namespace weft {

struct ContactLawJacobian {
  Mat3 velocity = Mat3::Zero();  // d du / d w
  Mat3 normal = Mat3::Zero();    // d du / d n (unconstrained n; only tangent variations occur)
  Vec3 friction = Vec3::Zero();  // d du / d mu
};

// The Jacobian blocks of the law at free velocity `free` in `branch` (the branch the forward
// solve chose; branch is not re-derived, so a contact exactly on a branch boundary keeps the
// forward's choice).
ContactLawJacobian differentiateSignoriniCoulomb(ContactBranch branch, const Vec3& normal,
                                                 double friction, const Vec3& free);

}  // namespace weft
