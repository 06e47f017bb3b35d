// DiffCloth Sec. 5.1, "Continuity of branches in contact conditions" (Fig. 2): a cloth lying on
// an analytic sphere, friction mu swept across the stick-slip threshold. Switching nodes between
// the slip and stick branches must not make the result jump: halving the mu spacing halves the
// largest speed difference between neighbouring samples (a jump would keep it), the speed falls
// monotonically with mu, and the threshold where the cloth comes to a stop lies where friction
// can hold its weight (mean tan of the polar angle of its nodes).

#include "ContactTestSupport.h"

#include <support/SceneBuilder.h>
#include <weft/mesh/SphereProjection.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace weft {
namespace {

constexpr double kRadius = 2.0, kSkin = 1e-3;
constexpr int kQuads = 10, kSteps = 30;

// The 0.6 m cloth's near edge at 0.05 R from the sphere's axis: its nodes' polar angles have
// tangents from 0.05 to 0.4.
Scene lyingCloth(double mu) {
  nlohmann::json doc = test::clothScene(0.6, kQuads, Vec3(0.05 * kRadius + 0.3, 0.0, 0.0),
                                        1.0 / 180, 1000.0, 1e-4, 0.2);
  test::addObstacle(doc, "sphere", {{"center", {0, 0, 0}}, {"radius", kRadius}}, mu);
  doc["obstacles"][0]["thickness"] = kSkin;
  doc["solver"]["contact"] = "newton";
  doc["solver"]["pd_tolerance"] = 1e-5;
  Scene scene = test::parse(doc);
  scene.cloths[0].mesh = projectOntoSphere(scene.cloths[0].mesh, Vec3::Zero(), kRadius + kSkin);
  return scene;
}

struct Sweep {
  std::vector<double> mu, speed;  // speed: the centre node's after kSteps steps
  int unconverged = 0;
};

Sweep sweep(int samples, double muMax) {
  Sweep s;
  const int centre = (kQuads / 2) * (kQuads + 1) + kQuads / 2;
  for (int k = 0; k < samples; ++k) {
    const double mu = muMax * k / (samples - 1);
    const Scene scene = lyingCloth(mu);
    Simulator sim(scene);
    for (int n = 0; n < kSteps; ++n) s.unconverged += !sim.step().converged;
    s.mu.push_back(mu);
    s.speed.push_back(sim.velocities().row(centre).norm());
  }
  return s;
}

double largestDifference(const std::vector<double>& v, int stride) {
  double worst = 0.0;
  for (std::size_t k = stride; k < v.size(); k += stride)
    worst = std::max(worst, std::abs(v[k] - v[k - stride]));
  return worst;
}

TEST(FrictionSweepContinuity, SpeedIsContinuousAcrossTheStickSlipThreshold) {
  const Scene probe = lyingCloth(0.0);
  double meanTan = 0.0;
  const NodeMatrix& x = probe.cloths[0].mesh.vertices;
  for (int i = 0; i < x.rows(); ++i) meanTan += std::hypot(x(i, 0), x(i, 2)) / x(i, 1);
  meanTan /= double(x.rows());

  const Sweep s = sweep(17, 0.35);  // spacing 0.021875
  EXPECT_EQ(s.unconverged, 0);
  for (std::size_t k = 1; k < s.speed.size(); ++k)
    EXPECT_LE(s.speed[k], s.speed[k - 1] + 1e-9) << "speed rises with mu at mu = " << s.mu[k];
  double stopsAt = 1.0;  // the first mu whose cloth is at rest
  for (std::size_t k = 0; k < s.speed.size(); ++k)
    if (s.speed[k] < 1e-6) {
      stopsAt = s.mu[k];
      break;
    }
  RecordProperty("mean_tan", std::to_string(meanTan));
  RecordProperty("stops_at_mu", std::to_string(stopsAt));
  EXPECT_GT(s.speed.front(), 0.1);  // frictionless: sliding
  EXPECT_GT(stopsAt, 0.9 * meanTan);
  EXPECT_LT(stopsAt, 1.1 * meanTan + 0.022);  // within one sample of the threshold
  // Continuity: the largest difference at the full spacing is about half that at twice the
  // spacing (0.5 for a curve whose steepest part is linear); a jump would keep it near 1.
  const double fine = largestDifference(s.speed, 1), coarse = largestDifference(s.speed, 2);
  RecordProperty("halving_ratio", std::to_string(fine / coarse));
  EXPECT_LT(fine / coarse, 0.6) << "fine " << fine << " coarse " << coarse;
}

}  // namespace
}  // namespace weft
