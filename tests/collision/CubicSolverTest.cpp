// The cubic solver behind continuous collision detection (Liang 2019 Eq. 5): against closed-form
// roots for three distinct roots, a double and a triple root, the linear and quadratic
// degenerations (a or b zero, or a negligible), roots at the interval's ends, and cubics with no
// root in [0, 1].

#include <weft/collision/PairCcd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace weft::collision {
namespace {

// Coefficients of k (t - r0)(t - r1)(t - r2).
std::array<double, 4> fromRoots(double r0, double r1, double r2, double k = 1.0) {
  return {k, -k * (r0 + r1 + r2), k * (r0 * r1 + r1 * r2 + r0 * r2), -k * r0 * r1 * r2};
}

CubicRoots solve(const std::array<double, 4>& c) {
  return solveCubic(c[0], c[1], c[2], c[3]);
}

TEST(CollisionCubic, ThreeDistinctRoots) {
  for (double k : {1.0, -3.0, 1e-9, 1e6}) {
    const CubicRoots r = solve(fromRoots(0.8, 0.1, 0.4, k));
    ASSERT_EQ(r.count, 3) << "k = " << k;
    EXPECT_NEAR(r.t[0], 0.1, 1e-14);
    EXPECT_NEAR(r.t[1], 0.4, 1e-14);
    EXPECT_NEAR(r.t[2], 0.8, 1e-14);
  }
}

TEST(CollisionCubic, RootsOutsideTheIntervalAreNotReported) {
  const CubicRoots r = solve(fromRoots(-1.0, 0.25, 2.0));
  ASSERT_EQ(r.count, 1);
  EXPECT_NEAR(r.t[0], 0.25, 1e-14);
  EXPECT_EQ(solve(fromRoots(-1.0, 2.0, 3.0)).count, 0);
  EXPECT_EQ(solve(fromRoots(1.5, 1.5, -0.5)).count, 0);
  // t^2 + 1 (no real root) and t^3 + t + 1 (one root near -0.68).
  EXPECT_EQ(solveCubic(0.0, 1.0, 0.0, 1.0).count, 0);
  EXPECT_EQ(solveCubic(1.0, 0.0, 1.0, 1.0).count, 0);
}

TEST(CollisionCubic, DoubleRootIsFoundOnce) {
  // (t - 0.5)^2 (t - 0.2): the double root is a critical point where the cubic touches zero.
  const CubicRoots r = solve(fromRoots(0.5, 0.5, 0.2));
  ASSERT_EQ(r.count, 2);
  EXPECT_NEAR(r.t[0], 0.2, 1e-14);
  EXPECT_NEAR(r.t[1], 0.5, 1e-8);
  // A double root alone, of either sign: (t - 0.3)^2 (t + 2), -(t - 0.7)^2 (t - 5).
  const CubicRoots touch = solve(fromRoots(0.3, 0.3, -2.0));
  ASSERT_EQ(touch.count, 1);
  EXPECT_NEAR(touch.t[0], 0.3, 1e-8);
  const CubicRoots touchBelow = solve(fromRoots(0.7, 0.7, 5.0, -1.0));
  ASSERT_EQ(touchBelow.count, 1);
  EXPECT_NEAR(touchBelow.t[0], 0.7, 1e-8);
}

TEST(CollisionCubic, NearDoubleRoots) {
  // Two roots 1e-4 apart: the critical point between them splits the bracket.
  const CubicRoots r = solve(fromRoots(0.6, 0.6 + 1e-4, 3.0));
  ASSERT_EQ(r.count, 2);
  // Conditioning: rounding of the coefficients (1e-16) over the slope there (about 2.4e-4).
  EXPECT_NEAR(r.t[0], 0.6, 1e-11);
  EXPECT_NEAR(r.t[1], 0.6 + 1e-4, 1e-11);
  // 1e-7 apart, the cubic between them is below the tolerance (1e-12 relative): one root, at
  // the critical point between them, as for a double root.
  const CubicRoots merged = solve(fromRoots(0.6, 0.6 + 1e-7, 3.0));
  ASSERT_EQ(merged.count, 1);
  EXPECT_NEAR(merged.t[0], 0.6 + 0.5e-7, 1e-9);
  // Nearly touching without a real root (the minimum 1e-6 above zero): none.
  const std::array<double, 4> c = fromRoots(0.6, 0.6, 3.0);
  EXPECT_EQ(solveCubic(c[0], c[1], c[2], c[3] - 1e-6).count, 0);
}

TEST(CollisionCubic, TripleRoot) {
  const CubicRoots r = solve(fromRoots(0.3, 0.3, 0.3));
  ASSERT_GE(r.count, 1);
  for (int i = 0; i < r.count; ++i) EXPECT_NEAR(r.t[i], 0.3, 1e-4);
}

TEST(CollisionCubic, LinearAndQuadraticDegenerations) {
  const CubicRoots linear = solveCubic(0.0, 0.0, 2.0, -1.0);
  ASSERT_EQ(linear.count, 1);
  EXPECT_NEAR(linear.t[0], 0.5, 1e-15);
  // (t - 0.25)(t - 0.75) with a = 0 exactly and with a negligible (1e-17).
  for (double a : {0.0, 1e-17, -1e-17}) {
    const CubicRoots quadratic = solveCubic(a, 1.0, -1.0, 0.1875);
    ASSERT_EQ(quadratic.count, 2) << "a = " << a;
    EXPECT_NEAR(quadratic.t[0], 0.25, 1e-14);
    EXPECT_NEAR(quadratic.t[1], 0.75, 1e-14);
  }
  // b = 0: t^3 - 0.125 has the single root 0.5.
  const CubicRoots noQuadratic = solveCubic(1.0, 0.0, 0.0, -0.125);
  ASSERT_EQ(noQuadratic.count, 1);
  EXPECT_NEAR(noQuadratic.t[0], 0.5, 1e-14);
  // A constant: no root, unless it is zero.
  EXPECT_EQ(solveCubic(0.0, 0.0, 0.0, 1.0).count, 0);
  EXPECT_TRUE(solveCubic(0.0, 0.0, 0.0, 0.0).identicallyZero);
}

TEST(CollisionCubic, RootsAtTheIntervalEnds) {
  const CubicRoots atZero = solve(fromRoots(0.0, 2.0, -1.0));
  ASSERT_EQ(atZero.count, 1);
  EXPECT_EQ(atZero.t[0], 0.0);
  const CubicRoots atOne = solve(fromRoots(1.0, 2.0, -1.0));
  ASSERT_EQ(atOne.count, 1);
  EXPECT_NEAR(atOne.t[0], 1.0, 1e-15);
  const CubicRoots both = solve(fromRoots(0.0, 1.0, 0.5));
  ASSERT_EQ(both.count, 3);
  EXPECT_NEAR(both.t[0], 0.0, 1e-15);
  EXPECT_NEAR(both.t[1], 0.5, 1e-14);
  EXPECT_NEAR(both.t[2], 1.0, 1e-15);
}

TEST(CollisionCubic, RandomCubicsWithKnownRoots) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> root(-0.5, 1.5), scale(-3.0, 3.0);
  int checked = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    std::array<double, 3> r = {root(rng), root(rng), root(rng)};
    std::sort(r.begin(), r.end());
    if (r[1] - r[0] < 1e-3 || r[2] - r[1] < 1e-3) continue;  // simple, well separated roots
    const double k = std::pow(10.0, scale(rng));
    const CubicRoots found = solve(fromRoots(r[0], r[1], r[2], trial % 2 ? k : -k));
    std::vector<double> inside;
    bool nearAnEnd = false;
    for (double x : r) {
      nearAnEnd = nearAnEnd || std::abs(x) < 1e-6 || std::abs(x - 1.0) < 1e-6;
      if (x > 0.0 && x < 1.0) inside.push_back(x);
    }
    if (nearAnEnd) continue;
    ASSERT_EQ(found.count, static_cast<int>(inside.size())) << "trial " << trial;
    for (std::size_t i = 0; i < inside.size(); ++i) EXPECT_NEAR(found.t[i], inside[i], 1e-9);
    ++checked;
  }
  EXPECT_GT(checked, 15000);
}

}  // namespace
}  // namespace weft::collision
