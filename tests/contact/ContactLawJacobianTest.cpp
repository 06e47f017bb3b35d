// The Jacobian blocks of the Signorini-Coulomb law (ContactLawJacobian.h) against central finite
// differences of the per-node closed-form solve (SignoriniCoulomb.h) in isolation, in each branch.

#include <weft/contact/ContactLawJacobian.h>
#include <weft/contact/SignoriniCoulomb.h>

#include <gtest/gtest.h>

namespace weft {
namespace {

constexpr double kStep = 1e-6;

Vec3 law(const Vec3& normal, double friction, const Vec3& free, ContactBranch expected) {
  Vec3 change;
  const ContactBranch branch = solveSignoriniCoulomb(normal, friction, free, change);
  EXPECT_EQ(branch, expected) << "the finite-difference probe crossed a branch boundary";
  return change;
}

struct Case {
  const char* name;
  Vec3 normal;
  double friction;
  Vec3 free;
  ContactBranch branch;
};

class ContactLawJacobianTest : public ::testing::TestWithParam<Case> {};

TEST_P(ContactLawJacobianTest, BlocksMatchFiniteDifferencesOfTheClosedForm) {
  const Case& c = GetParam();
  const Vec3 n = c.normal.normalized();
  Vec3 change;
  ASSERT_EQ(solveSignoriniCoulomb(n, c.friction, c.free, change), c.branch);
  const ContactLawJacobian j = differentiateSignoriniCoulomb(c.branch, n, c.friction, c.free);
  Mat3 byVelocity, byNormal;
  for (int k = 0; k < 3; ++k) {
    const Vec3 e = kStep * Vec3::Unit(k);
    byVelocity.col(k) =
        (law(n, c.friction, c.free + e, c.branch) - law(n, c.friction, c.free - e, c.branch)) /
        (2.0 * kStep);
    // The closed form takes n as given (unnormalised probes are fine: the blocks are for an
    // unconstrained n).
    byNormal.col(k) =
        (law(n + e, c.friction, c.free, c.branch) - law(n - e, c.friction, c.free, c.branch)) /
        (2.0 * kStep);
  }
  const Vec3 byFriction = (law(n, c.friction + kStep, c.free, c.branch) -
                           law(n, c.friction - kStep, c.free, c.branch)) /
                          (2.0 * kStep);
  const double scale = 1.0 + c.free.norm();
  EXPECT_LT((j.velocity - byVelocity).norm(), 1e-7 * scale) << "d du/dw\n"
                                                            << j.velocity << "\nfd\n"
                                                            << byVelocity;
  EXPECT_LT((j.normal - byNormal).norm(), 1e-7 * scale) << "d du/dn\n"
                                                        << j.normal << "\nfd\n"
                                                        << byNormal;
  EXPECT_LT((j.friction - byFriction).norm(), 1e-7 * scale)
      << "d du/dmu " << j.friction.transpose();
}

INSTANTIATE_TEST_SUITE_P(
    Branches, ContactLawJacobianTest,
    ::testing::Values(
        Case{"TakeOff", Vec3(0, 1, 0), 0.3, Vec3(0.2, 0.5, -0.1), ContactBranch::TakeOff},
        Case{"Stick", Vec3(0, 1, 0), 0.5, Vec3(0.1, -1.0, 0.2), ContactBranch::Stick},
        Case{"StickTiltedNormal", Vec3(-0.34, 0.94, 0.1), 0.8, Vec3(0.2, -0.7, 0.1),
             ContactBranch::Stick},
        Case{"Slip", Vec3(0, 1, 0), 0.3, Vec3(0.8, -0.5, -0.4), ContactBranch::Slip},
        Case{"SlipTiltedNormal", Vec3(0.3, 0.9, -0.2), 0.2, Vec3(-1.1, -0.3, 0.7),
             ContactBranch::Slip},
        Case{"SlipWithoutFriction", Vec3(0, 0, 1), 0.0, Vec3(0.4, 0.3, -0.9), ContactBranch::Slip}),
    [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

TEST(ContactLawJacobian, StickAndTakeOffHaveNoFrictionOrNormalDependence) {
  const Vec3 n = Vec3::UnitY();
  const ContactLawJacobian stick =
      differentiateSignoriniCoulomb(ContactBranch::Stick, n, 0.5, Vec3(0.1, -1, 0));
  EXPECT_TRUE(stick.velocity.isApprox(-Mat3::Identity()));
  EXPECT_TRUE(stick.normal.isZero(0.0));
  EXPECT_TRUE(stick.friction.isZero(0.0));
  const ContactLawJacobian off =
      differentiateSignoriniCoulomb(ContactBranch::TakeOff, n, 0.5, Vec3(0.1, 1, 0));
  EXPECT_TRUE(off.velocity.isZero(0.0));
}

}  // namespace
}  // namespace weft
