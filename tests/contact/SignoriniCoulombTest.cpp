// The local Signorini-Coulomb law of one contact (DiffCloth Eq. 8): for random normals,
// friction coefficients and free velocities, the closed form returns a velocity change whose
// impulse and resulting velocity satisfy the branch it claims, and the branch is the one the
// free velocity calls for.

#include "ContactTestSupport.h"

#include <weft/contact/SignoriniCoulomb.h>

#include <gtest/gtest.h>

#include <random>

namespace weft {
namespace {

ContactPoint solved(const Vec3& normal, double mu, const Vec3& free, double mass) {
  Vec3 du;
  ContactPoint p;
  p.branch = solveSignoriniCoulomb(normal, mu, free, du);
  p.normal = normal;
  p.friction = mu;
  p.effectiveMass = mass;
  p.velocity = free + du;
  p.impulse = mass * du;
  return p;
}

TEST(SignoriniCoulomb, RandomInputsSatisfyTheClaimedBranch) {
  std::mt19937 rng(1);
  std::normal_distribution<double> g(0.0, 1.0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double frictions[] = {0.0, 0.1, 0.5, 1.0, 3.0, 100.0};
  int count[4] = {0, 0, 0, 0};
  for (int k = 0; k < 20000; ++k) {
    const Vec3 n = Vec3(g(rng), g(rng), g(rng)).normalized();
    const double mu = frictions[k % 6];
    const Vec3 free = std::pow(10.0, 4.0 * u(rng) - 2.0) * Vec3(g(rng), g(rng), g(rng));
    const double mass = std::pow(10.0, 3.0 * u(rng) - 5.0);
    const ContactPoint p = solved(n, mu, free, mass);
    ASSERT_EQ(test::branchViolation(p, 1e-12), "") << "k = " << k << ", mu = " << mu;
    // The branch the free velocity calls for (Eq. 8): which one is unique.
    const double fN = free.dot(n), fT = (free - fN * n).norm();
    const ContactBranch expected = fN >= 0.0        ? ContactBranch::TakeOff
                                   : fT <= mu * -fN ? ContactBranch::Stick
                                                    : ContactBranch::Slip;
    ASSERT_EQ(p.branch, expected) << "k = " << k;
    ++count[static_cast<int>(p.branch)];
  }
  // All three branches were exercised.
  EXPECT_GT(count[1], 1000);
  EXPECT_GT(count[2], 1000);
  EXPECT_GT(count[3], 1000);
}

// The law's mass is a free parameter of the iteration, not of the solution (ContactSolver::
// setContacts): a pair (r, u) the law returns with one mass m1 is returned unchanged with any
// other m2 from the free velocity w2 = u - r / m2, in the same branch. The Newton contact solve
// relies on it to solve with sqrt(m P_ii) and record with the lumped mass.
TEST(SignoriniCoulomb, SolutionDoesNotDependOnTheMassItIsSolvedWith) {
  std::mt19937 rng(2);
  std::normal_distribution<double> g(0.0, 1.0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double frictions[] = {0.0, 0.1, 0.5, 1.0, 3.0};
  int switched = 0;
  for (int k = 0; k < 20000; ++k) {
    const Vec3 n = Vec3(g(rng), g(rng), g(rng)).normalized();
    const double mu = frictions[k % 5];
    const Vec3 free = std::pow(10.0, 4.0 * u(rng) - 2.0) * Vec3(g(rng), g(rng), g(rng));
    const double m1 = std::pow(10.0, 3.0 * u(rng) - 5.0);
    const double m2 = m1 * std::pow(10.0, 6.0 * u(rng) - 3.0);
    const ContactPoint first = solved(n, mu, free, m1);
    const Vec3 free2 = first.velocity - first.impulse / m2;
    const ContactPoint second = solved(n, mu, free2, m2);
    const double scale = first.impulse.norm() + m1 * first.velocity.norm() + 1e-300;
    // On a branch boundary (|w_T| = mu |w_N| or w_N = 0) either label is right; the pair must
    // still be the same.
    const bool boundary = second.branch != first.branch;
    switched += boundary;
    ASSERT_LT((second.impulse - first.impulse).norm(), 1e-9 * scale) << "k = " << k;
    ASSERT_LT(m1 * (second.velocity - first.velocity).norm(), 1e-9 * scale) << "k = " << k;
    if (boundary) {
      ASSERT_EQ(test::branchViolation(second, 1e-9), "") << "k = " << k;
    }
  }
  EXPECT_LT(switched, 200) << "branch labels should agree away from the boundaries";
}

TEST(SignoriniCoulomb, EdgeCases) {
  const Vec3 n = Vec3::UnitY();
  // Resting with no tangential motion and no friction: stick with zero friction force.
  ContactPoint p = solved(n, 0.0, Vec3(0, -1, 0), 2.0);
  EXPECT_EQ(p.branch, ContactBranch::Stick);
  EXPECT_EQ(p.impulse, Vec3(0, 2, 0));
  // Frictionless sliding: slip, normal velocity removed, tangential kept.
  p = solved(n, 0.0, Vec3(3, -1, 0), 2.0);
  EXPECT_EQ(p.branch, ContactBranch::Slip);
  EXPECT_TRUE(p.velocity.isApprox(Vec3(3, 0, 0)));
  // Exactly on the cone: stick (the test is <=).
  p = solved(n, 0.5, Vec3(0.5, -1, 0), 1.0);
  EXPECT_EQ(p.branch, ContactBranch::Stick);
  // Grazing (u_N = 0): take-off, no force.
  p = solved(n, 0.5, Vec3(1, 0, 0), 1.0);
  EXPECT_EQ(p.branch, ContactBranch::TakeOff);
  EXPECT_EQ(p.impulse, Vec3::Zero());
  // Slip off the cone: friction takes mu |u_N| off the tangential speed.
  p = solved(n, 0.5, Vec3(2, -1, 0), 1.0);
  EXPECT_EQ(p.branch, ContactBranch::Slip);
  EXPECT_TRUE(p.velocity.isApprox(Vec3(1.5, 0, 0)));
  EXPECT_TRUE(p.impulse.isApprox(Vec3(-0.5, 1, 0)));
}

}  // namespace
}  // namespace weft
