// Handle trajectories: keyframes interpolate linearly and hold at the ends; the cubic Hermite
// spline passes through its points with its tangents; rotation turns about the given axis.

#include <support/SceneBuilder.h>
#include <weft/scene/HandleTrajectory.h>

#include <gtest/gtest.h>

#include <cmath>

namespace weft {
namespace {

HandleTrajectory keyframes() {
  HandleTrajectory t;
  t.kind = HandleTrajectory::Kind::Keyframes;
  t.times = {0.5, 1.0, 2.0};
  t.offsets = {Vec3(0, 0, 0), Vec3(1, -2, 0.5), Vec3(1, 0, 4.5)};
  return t;
}

TEST(HandleTrajectory, KeyframesAreHitExactly) {
  const HandleTrajectory t = keyframes();
  for (std::size_t k = 0; k < t.times.size(); ++k) EXPECT_EQ(t.offset(t.times[k]), t.offsets[k]);
}

TEST(HandleTrajectory, KeyframesInterpolateLinearly) {
  const HandleTrajectory t = keyframes();
  for (double s : {0.1, 0.25, 0.5, 0.9}) {
    const double a = 0.5 + 0.5 * s, b = 1.0 + 1.0 * s;
    EXPECT_NEAR((t.offset(a) - ((1 - s) * t.offsets[0] + s * t.offsets[1])).norm(), 0.0, 1e-15)
        << a;
    EXPECT_NEAR((t.offset(b) - ((1 - s) * t.offsets[1] + s * t.offsets[2])).norm(), 0.0, 1e-15)
        << b;
  }
}

TEST(HandleTrajectory, KeyframesHoldAtTheEnds) {
  const HandleTrajectory t = keyframes();
  EXPECT_EQ(t.offset(0.0), t.offsets.front());
  EXPECT_EQ(t.offset(-3.0), t.offsets.front());
  EXPECT_EQ(t.offset(2.5), t.offsets.back());
  EXPECT_EQ(t.offset(100.0), t.offsets.back());
  HandleTrajectory single;
  single.times = {1.0};
  single.offsets = {Vec3(1, 2, 3)};
  EXPECT_EQ(single.offset(0.0), Vec3(1, 2, 3));
  EXPECT_EQ(single.offset(5.0), Vec3(1, 2, 3));
}

// A vector cubic p(t) = a + b t + c t^2 + d t^3 and its derivative.
Vec3 cubic(double t) {
  return Vec3(0.3, -1, 2) + Vec3(1, 0.5, -2) * t + Vec3(-0.7, 2, 0.1) * t * t +
         Vec3(0.2, -0.4, 1.3) * t * t * t;
}
Vec3 cubicDerivative(double t) {
  return Vec3(1, 0.5, -2) + 2 * Vec3(-0.7, 2, 0.1) * t + 3 * Vec3(0.2, -0.4, 1.3) * t * t;
}

HandleTrajectory hermiteFromCubic(const std::vector<double>& times) {
  HandleTrajectory h;
  h.kind = HandleTrajectory::Kind::Hermite;
  h.times = times;
  for (double t : times) h.offsets.push_back(cubic(t)), h.tangents.push_back(cubicDerivative(t));
  return h;
}

TEST(HandleTrajectory, HermitePassesThroughItsPointsWithItsTangents) {
  HandleTrajectory h;
  h.kind = HandleTrajectory::Kind::Hermite;
  h.times = {0.0, 0.4, 1.5, 2.0};
  h.offsets = {Vec3(0, 0, 0), Vec3(0.2, 0.5, -0.1), Vec3(1, 0.1, 0.3), Vec3(1.2, 1.2, 1.2)};
  h.tangents = {Vec3(1, 0, 0), Vec3(0, 2, 0), Vec3(-1, 0.5, 3), Vec3(0, 0, -2)};
  // Second-order one-sided differences, so the check sees each knot's own interval only.
  const double e = 1e-5;
  for (std::size_t k = 0; k < h.times.size(); ++k) {
    const double t = h.times[k];
    const double tol = 1e-6 * (1 + h.tangents[k].norm());
    EXPECT_NEAR((h.offset(t) - h.offsets[k]).norm(), 0.0, 1e-14) << "knot " << k;
    if (k + 1 < h.times.size()) {
      const Vec3 right = (-3 * h.offset(t) + 4 * h.offset(t + e) - h.offset(t + 2 * e)) / (2 * e);
      EXPECT_NEAR((right - h.tangents[k]).norm(), 0.0, tol) << "knot " << k << " from the right";
    }
    if (k > 0) {  // interior knots: the same tangent from both sides (C1)
      const Vec3 left = (3 * h.offset(t) - 4 * h.offset(t - e) + h.offset(t - 2 * e)) / (2 * e);
      EXPECT_NEAR((left - h.tangents[k]).norm(), 0.0, tol) << "knot " << k << " from the left";
    }
  }
}

TEST(HandleTrajectory, HermiteReproducesACubicExactly) {
  // Points and tangents sampled from one cubic: the Hermite interpolant is that cubic on every
  // interval, whatever the (unequal) interval lengths; this checks the tangent scaling.
  const HandleTrajectory h = hermiteFromCubic({-0.5, 0.2, 0.7, 1.9});
  for (double t = -0.5; t <= 1.9; t += 0.0625) {
    EXPECT_NEAR((h.offset(t) - cubic(t)).norm(), 0.0, 1e-12) << "t = " << t;
    const double e = 1e-6;
    if (t - e > -0.5 && t + e < 1.9) {
      const Vec3 fd = (h.offset(t + e) - h.offset(t - e)) / (2 * e);
      EXPECT_NEAR((fd - cubicDerivative(t)).norm(), 0.0, 1e-7) << "t = " << t;
    }
  }
}

TEST(HandleTrajectory, HermiteHoldsAtTheEnds) {
  const HandleTrajectory h = hermiteFromCubic({0.0, 1.0});
  EXPECT_EQ(h.offset(-1.0), h.offsets.front());
  EXPECT_EQ(h.offset(3.0), h.offsets.back());
}

TEST(HandleTrajectory, RotationTurnsAboutTheAxisThroughTheCentreThenOffsets) {
  HandleTrajectory t;
  t.times = {0.0, 1.0};
  t.offsets = {Vec3(0, 0, 0), Vec3(0, 1, 0)};
  t.rotates = true;
  t.rotationCenter = Vec3(1, 0, 0);
  t.rotationAxis = Vec3::UnitY();
  t.rotationRateDeg = 90.0;
  // After 1 s: 90 degrees about +Y through (1,0,0): (2,0,0) -> (1,0,-1); then offset (0,1,0).
  EXPECT_NEAR((t.target(Vec3(2, 0, 0), 1.0) - Vec3(1, 1, -1)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((t.target(Vec3(2, 0, 0), 0.0) - Vec3(2, 0, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((t.target(Vec3(1, 5, 0), 0.7) - Vec3(1, 5.7, 0)).norm(), 0.0, 1e-15);  // on the axis
}

TEST(HandleTrajectory, SceneReadsHermiteAndKeyframes) {
  nlohmann::json doc = test::hangingClothScene(1.0, 2, 0.01, 10, 100.0);
  doc["cloths"][0]["attachments"] = {
      {{"vertices", {0}},
       {"kind", "handle"},
       {"trajectory",
        {{"hermite",
          {{"times", {0, 1}},
           {"points", {{0, 0, 0}, {1, 0, 0}}},
           {"tangents", {{0, 0, 0}, {0, 0, 0}}}}}}}},
      {{"vertices", {2}},
       {"kind", "handle"},
       {"trajectory",
        {{"keyframes",
          {{{"time", 0}, {"offset", {0, 0, 0}}}, {{"time", 2}, {"offset", {0, 2, 0}}}}}}}}};
  const Scene s = test::parse(doc);
  const HandleTrajectory& h = s.cloths[0].attachments[0].trajectory;
  EXPECT_EQ(h.kind, HandleTrajectory::Kind::Hermite);
  EXPECT_NEAR(h.offset(0.5).x(), 0.5, 1e-15);  // smoothstep midpoint
  EXPECT_NEAR(h.offset(0.25).x(), 3 * 0.0625 - 2 * 0.015625, 1e-15);
  const HandleTrajectory& k = s.cloths[0].attachments[1].trajectory;
  EXPECT_EQ(k.kind, HandleTrajectory::Kind::Keyframes);
  EXPECT_NEAR(k.offset(0.5).y(), 0.5, 1e-15);
}

}  // namespace
}  // namespace weft
