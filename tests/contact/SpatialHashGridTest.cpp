// The self-collision broad phase: the spatial hash reports exactly the overlapping box pairs a
// brute-force O(n^2) scan finds, once each, whatever the cell size; and the swept-path
// self-collision detector built on it finds exactly the pairs a brute-force pair test finds.

#include <weft/contact/SelfCollisionDetector.h>
#include <weft/contact/SpatialHashGrid.h>
#include <weft/model/ClothModel.h>

#include <support/SceneBuilder.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

namespace weft {
namespace {

std::set<std::pair<int, int>> bruteForcePairs(const std::vector<Vec3>& lower,
                                              const std::vector<Vec3>& upper) {
  std::set<std::pair<int, int>> pairs;
  for (std::size_t a = 0; a < lower.size(); ++a)
    for (std::size_t b = a + 1; b < lower.size(); ++b)
      if ((lower[a].array() <= upper[b].array()).all() &&
          (lower[b].array() <= upper[a].array()).all())
        pairs.emplace(static_cast<int>(a), static_cast<int>(b));
  return pairs;
}

class SpatialHash : public ::testing::TestWithParam<double> {};

TEST_P(SpatialHash, FindsExactlyTheBruteForcePairsOnce) {
  const double cellSize = GetParam();
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> position(-0.5, 0.5), size(0.0, 0.08);
  std::vector<Vec3> lower, upper;
  for (int i = 0; i < 1200; ++i) {
    const Vec3 lo(position(rng), position(rng), position(rng));
    lower.push_back(lo);
    upper.push_back(lo + Vec3(size(rng), size(rng), size(rng)));
  }
  // A few degenerate and large boxes, and two identical ones, for the corner cases.
  lower.push_back(Vec3(0.1, 0.1, 0.1)), upper.push_back(Vec3(0.1, 0.1, 0.1));
  lower.push_back(Vec3(0.1, 0.1, 0.1)), upper.push_back(Vec3(0.1, 0.1, 0.1));
  lower.push_back(Vec3(-0.4, -0.1, -0.2)), upper.push_back(Vec3(0.3, 0.0, 0.2));
  const auto expected = bruteForcePairs(lower, upper);
  ASSERT_GT(expected.size(), 300u);

  SpatialHashGrid grid;
  std::vector<std::pair<int, int>> found;
  for (int repeat = 0; repeat < 2; ++repeat) {  // buffers reused on the second call
    found.clear();
    grid.overlappingPairs(lower, upper, cellSize, found);
    std::vector<std::pair<int, int>> sorted = found;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end())
        << "a pair reported twice";
    for (const auto& p : found) ASSERT_LT(p.first, p.second);
    const std::set<std::pair<int, int>> unique(found.begin(), found.end());
    EXPECT_EQ(unique, expected);
  }
}

// Cells much smaller than, about, and much larger than the boxes.
INSTANTIATE_TEST_SUITE_P(CellSizes, SpatialHash, ::testing::Values(0.011, 0.05, 0.3, 2.0));

TEST(SelfCollisionDetector, FindsExactlyTheBruteForceSweptPairs) {
  // A crumpled state: a 12 x 12 cloth with random positions in a small box and random motion.
  nlohmann::json doc = test::gridScene(0.5, 12, 0.01, 0);
  doc["cloths"][0]["self_collision"] = {{"radius", 0.03}, {"friction", 0.2}};
  const Scene scene = test::parse(doc);
  const ClothModel model = buildClothModel(scene);
  SelfCollisionDetector detector(scene, model);
  const int m = model.nodeCount();
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  NodeMatrix x(m, 3), d(m, 3);
  for (int i = 0; i < m; ++i) {
    x.row(i) = 0.15 * Vec3(u(rng), u(rng), u(rng)).transpose();
    d.row(i) = Vec3(0.2, -0.1, 0.05).transpose() + 0.03 * Vec3(u(rng), u(rng), u(rng)).transpose();
  }
  std::vector<ContactPoint> pairs;
  detector.detect(x, d, 0.01, pairs);

  std::set<std::pair<int, int>> expected;
  for (int a = 0; a < m; ++a)
    for (int b = a + 1; b < m; ++b) {
      const Vec3 dx = x.row(a) - x.row(b), dd = d.row(a) - d.row(b);
      double closest = std::min(dx.norm(), (dx + dd).norm());
      const double tau = -dx.dot(dd) / dd.squaredNorm();
      if (tau > 0.0 && tau < 1.0) closest = std::min(closest, (dx + tau * dd).norm());
      const double reach =
          (1.0 + SelfCollisionDetector::kMarginFraction) * detector.collisionDistance(a, b);
      if (closest < reach && !detector.excluded(a, b)) expected.emplace(a, b);
    }
  ASSERT_GT(expected.size(), 100u);
  std::set<std::pair<int, int>> found;
  for (const ContactPoint& c : pairs) {
    found.emplace(c.node, c.partner);
    EXPECT_NEAR(c.normal.norm(), 1.0, 1e-12);
    // Normal from partner to node, at the start of the step.
    EXPECT_GT(c.normal.dot(Vec3(x.row(c.node) - x.row(c.partner))), 0.0);
  }
  EXPECT_EQ(found.size(), pairs.size()) << "a pair reported twice";
  EXPECT_EQ(found, expected);
}

}  // namespace
}  // namespace weft
