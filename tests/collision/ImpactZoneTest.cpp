// The impact-zone response (Liang et al. 2019 Sec. 3.4): a sheet of points falling onto a floor
// of fixed nodes, zones merging through a shared node, the round cap, the rigid failsafe, and
// the backward pass of the whole map against central differences through apply().
//
// Two test detectors stand in for the CCD: a brute-force vertex-face proximity test against
// the floor's triangles at the end positions, and a fixed list of impacts (normals and weights
// given) returned whenever their constraint is violated, whose G and h do not depend on the
// positions, so that central differences through apply() see the map with G, h held fixed.

#include <weft/collision/ImpactZones.h>

#include <gtest/gtest.h>

#include <limits>
#include <random>

namespace weft::collision {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kThickness = 1e-3;
// Detection threshold below the thickness: a resolved impact (normal . s >= thickness up to
// round-off) must not be found again.
constexpr double kDetectSlack = 1e-9;

double separation(const Impact& impact, const NodeMatrix& x) {
  Vec3 s = Vec3::Zero();
  for (int k = 0; k < 4; ++k)
    if (impact.nodes[k] >= 0) s += impact.weights[k] * x.row(impact.nodes[k]).transpose();
  return impact.normal.dot(s);
}

// Vertex-face proximity of every free vertex against every triangle (fixed nodes), at the end
// positions, inside the triangle and on the side the vertex started on.
ImpactDetector floorDetector(const Eigen::VectorXd& masses,
                             const std::vector<Eigen::Vector3i>& tris) {
  return [masses, tris](const NodeMatrix& start, const NodeMatrix& end) {
    std::vector<Impact> impacts;
    for (int v = 0; v < end.rows(); ++v) {
      if (!std::isfinite(masses[v])) continue;
      for (const Eigen::Vector3i& t : tris) {
        const Vec3 a = end.row(t[0]), b = end.row(t[1]), c = end.row(t[2]);
        Vec3 n = (b - a).cross(c - a).normalized();
        if (n.dot(start.row(v).transpose() - start.row(t[0]).transpose()) < 0) n = -n;
        const Vec3 p = end.row(v).transpose();
        const double d1 = n.dot(p - a);
        if (d1 >= kThickness - kDetectSlack) continue;
        // Barycentric coordinates of p's projection onto the triangle.
        const Vec3 q = p - d1 * n;
        const double area = (b - a).cross(c - a).dot(n);
        const double b0 = (b - q).cross(c - q).dot(n) / area;
        const double b1 = (c - q).cross(a - q).dot(n) / area;
        const double b2 = 1.0 - b0 - b1;
        if (b0 < -1e-9 || b1 < -1e-9 || b2 < -1e-9) continue;
        const double d0 = n.dot(start.row(v).transpose() - start.row(t[0]).transpose());
        Impact impact;
        impact.kind = ImpactKind::VertexFace;
        impact.nodes = {v, t[0], t[1], t[2]};
        impact.weights = {1.0, -b0, -b1, -b2};
        impact.normal = n;
        impact.time = d0 > d1 ? std::clamp((d0 - kThickness) / (d0 - d1), 0.0, 1.0) : 0.0;
        impacts.push_back(impact);
      }
    }
    return impacts;
  };
}

// The impacts of a fixed list whose constraint is violated at the end positions.
ImpactDetector listDetector(const std::vector<Impact>& candidates) {
  return [candidates](const NodeMatrix&, const NodeMatrix& end) {
    std::vector<Impact> impacts;
    for (const Impact& impact : candidates)
      if (separation(impact, end) < kThickness - kDetectSlack) impacts.push_back(impact);
    return impacts;
  };
}

Impact makeImpact(ImpactKind kind, std::array<int, 4> nodes, std::array<double, 4> weights,
                  const Vec3& normal, double time) {
  Impact impact;
  impact.kind = kind;
  impact.nodes = nodes;
  impact.weights = weights;
  impact.normal = normal.normalized();
  impact.time = time;
  return impact;
}

ImpactZoneOptions options() {
  ImpactZoneOptions o;
  o.thickness = kThickness;
  return o;
}

// A 5 x 5 sheet of points (nodes 0-24) over a floor square of two fixed triangles (nodes 25-28)
// at height 0. Most points fall through the floor; row 4 stops above it.
struct FallingSheet {
  NodeMatrix x0, x1;
  Eigen::VectorXd masses;
  std::vector<Eigen::Vector3i> tris{Eigen::Vector3i(25, 26, 27), Eigen::Vector3i(25, 27, 28)};
  FallingSheet() {
    x0.resize(29, 3);
    x1.resize(29, 3);
    masses.resize(29);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> jitter(-0.01, 0.01), mass(0.5, 2.0);
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 5; ++j) {
        const int v = 5 * i + j;
        x0.row(v) << 0.1 + 0.2 * j + jitter(rng), 0.1 + 0.2 * i + jitter(rng), 0.05;
        const double drop = i == 4 ? 0.02 : 0.1 + jitter(rng);
        x1.row(v) = x0.row(v) + Eigen::RowVector3d(0.02 * jitter(rng), 0.0, -drop);
        masses[v] = mass(rng);
      }
    const double corners[4][2] = {{-1, -1}, {2, -1}, {2, 2}, {-1, 2}};
    for (int k = 0; k < 4; ++k) {
      x0.row(25 + k) << corners[k][0], corners[k][1], 0.0;
      x1.row(25 + k) = x0.row(25 + k);
      masses[25 + k] = kInf;
    }
  }
};

TEST(CollisionImpactZones, FallingSheetRestsAtThicknessAboveTheFloor) {
  const FallingSheet sheet;
  const ImpactZones zones(options());
  const ImpactZoneResult result =
      zones.apply(sheet.x0, sheet.x1, sheet.masses, floorDetector(sheet.masses, sheet.tris));
  const ImpactZoneStats& s = result.stats;
  EXPECT_TRUE(s.converged);
  EXPECT_FALSE(s.roundCapHit);
  EXPECT_TRUE(s.allQpConverged);
  EXPECT_EQ(s.rigidZones, 0);
  EXPECT_EQ(s.rounds, 2);  // one round of responses, then a clean detection
  EXPECT_EQ(s.zones, 20);  // every point of rows 0-3, each alone in its zone
  EXPECT_EQ(s.constraints, 20);
  EXPECT_EQ(s.qpSolves, 20);
  EXPECT_EQ(s.qpIterationsTotal, 20);
  EXPECT_EQ(s.qpIterationsMax, 1);
  EXPECT_LE(s.maxViolation, 1e-12);
  for (int v = 0; v < 25; ++v) {
    if (v < 20) {
      // One node against a plane: the mass-weighted projection is the vertical projection onto
      // the plane z = thickness, whatever the mass.
      EXPECT_NEAR(result.positions(v, 2), kThickness, 1e-15) << v;
      EXPECT_EQ(result.positions(v, 0), sheet.x1(v, 0));
      EXPECT_EQ(result.positions(v, 1), sheet.x1(v, 1));
    } else {
      EXPECT_EQ(result.positions.row(v), sheet.x1.row(v)) << v;  // in no zone: untouched
    }
  }
  for (int v = 25; v < 29; ++v) EXPECT_EQ(result.positions.row(v), sheet.x1.row(v));
  for (const ImpactZoneRecord& zone : result.zones) {
    ASSERT_EQ(zone.nodes.size(), 1u);
    ASSERT_EQ(zone.impacts.size(), 1u);
    EXPECT_GT(zone.solution.lambda[0], 0.0);
  }
}

// Nodes 0-3 free, 4-6 a fixed floor triangle at height 0, 7 free and never involved.
// A: node 0 on the floor, B: node 1 on the floor, C: edge (0,1) above edge (2,3). C shares nodes
// with A and B and comes later, so round 1 keeps A and B (two zones), round 2 keeps C, which
// merges both zones with nodes 2 and 3 into one.
struct MergingScene {
  NodeMatrix x0, x1;
  Eigen::VectorXd masses;
  std::vector<Impact> candidates;
  MergingScene() {
    x0.resize(8, 3);
    x0 << 0.0, 0.0, 0.1,  //
        1.0, 0.0, 0.1,    //
        0.3, -0.5, 0.0,   //
        0.3, 0.5, 0.0,    //
        -1.0, -1.0, 0.0,  //
        2.0, -1.0, 0.0,   //
        0.0, 2.0, 0.0,    //
        5.0, 5.0, 5.0;
    x1 = x0;
    x1.col(2).head(2).setConstant(-0.01);
    x1.col(2).segment(2, 2).setConstant(0.05);
    x1.row(7) << 5.0, 5.0, 4.0;
    masses.resize(8);
    masses << 1.0, 2.0, 0.5, 1.5, kInf, kInf, kInf, 1.0;
    const Vec3 up = Vec3::UnitZ();
    candidates.push_back(
        makeImpact(ImpactKind::VertexFace, {0, 4, 5, 6}, {1.0, -0.5, -0.25, -0.25}, up, 0.1));
    candidates.push_back(
        makeImpact(ImpactKind::VertexFace, {1, 4, 5, 6}, {1.0, -0.2, -0.4, -0.4}, up, 0.2));
    candidates.push_back(
        makeImpact(ImpactKind::EdgeEdge, {0, 1, 2, 3}, {0.7, 0.3, -0.5, -0.5}, up, 0.5));
  }
};

// ARCSim's rule (ImpactZoneOptions::independentImpacts): impacts sharing a free node wait.
TEST(CollisionImpactZones, ZonesSharingANodeMerge) {
  const MergingScene scene;
  ImpactZoneOptions o = options();
  o.independentImpacts = true;
  const ImpactZones zones(o);
  const ImpactZoneResult result =
      zones.apply(scene.x0, scene.x1, scene.masses, listDetector(scene.candidates));
  const ImpactZoneStats& s = result.stats;
  EXPECT_TRUE(s.converged);
  EXPECT_EQ(s.rounds, 3);
  EXPECT_EQ(s.impactsDetected, 3 + 1);  // A, B, C; then C again
  EXPECT_EQ(s.impactsKept, 3);
  EXPECT_EQ(s.qpSolves, 3);  // zone {0}, zone {1}, then the merged zone
  EXPECT_EQ(s.zones, 1);
  EXPECT_EQ(s.constraints, 3);
  EXPECT_LE(s.maxViolation, 1e-12);
  ASSERT_EQ(result.zones.size(), 1u);
  const ImpactZoneRecord& zone = result.zones[0];
  EXPECT_EQ(zone.nodes, (std::vector<int>{0, 1, 2, 3}));
  ASSERT_EQ(zone.qp.G.rows(), 3);
  ASSERT_EQ(zone.qp.G.cols(), 12);
  for (const Impact& impact : scene.candidates)
    EXPECT_GE(separation(impact, result.positions), kThickness - 1e-12);
  // The zone's solution is the minimum displacement from x1 for all three impacts (KKT).
  const ZoneQp& qp = zone.qp;
  const ZoneQpSolution& sol = zone.solution;
  EXPECT_LE(
      (qp.weights.cwiseProduct(sol.z - qp.x) + qp.G.transpose() * sol.lambda).cwiseAbs().maxCoeff(),
      1e-12);
  EXPECT_GE(sol.lambda.minCoeff(), 0.0);
  EXPECT_GT(sol.lambda[2], 0.0);  // C binds
  for (int v = 4; v < 8; ++v) EXPECT_EQ(result.positions.row(v), scene.x1.row(v));
}

// By default every impact of a round joins its zone at once: the same final zone, and so the
// same positions, in one round of responses instead of two; a zone solved sparsely (denseLimit
// 0) gives them too.
TEST(CollisionImpactZones, AllImpactsOfARoundJoinAtOnce) {
  const MergingScene scene;
  ImpactZoneOptions independent = options();
  independent.independentImpacts = true;
  const ImpactZoneResult reference =
      ImpactZones(independent)
          .apply(scene.x0, scene.x1, scene.masses, listDetector(scene.candidates));
  for (int denseLimit : {48, 0}) {
    SCOPED_TRACE(denseLimit);
    ImpactZoneOptions o = options();
    o.denseLimit = denseLimit;
    const ImpactZoneResult result =
        ImpactZones(o).apply(scene.x0, scene.x1, scene.masses, listDetector(scene.candidates));
    const ImpactZoneStats& s = result.stats;
    EXPECT_TRUE(s.converged);
    EXPECT_EQ(s.rounds, 2);
    EXPECT_EQ(s.impactsKept, 3);
    EXPECT_EQ(s.qpSolves, 1);
    EXPECT_EQ(s.zones, 1);
    EXPECT_EQ(s.constraints, 3);
    ASSERT_EQ(result.zones.size(), 1u);
    EXPECT_EQ(result.zones[0].sparse, denseLimit == 0);
    EXPECT_LE((result.positions - reference.positions).cwiseAbs().maxCoeff(), 1e-12);
    // The backward pass densifies a sparse zone: the same gradient either way.
    NodeMatrix dLdz = NodeMatrix::Zero(scene.x1.rows(), 3);
    for (Eigen::Index i = 0; i < dLdz.rows(); ++i) dLdz.row(i) << 0.3 * i, 1.0, -0.2 * i;
    const ImpactZoneBackward a = ImpactZones(o).backward(result, dLdz);
    const ImpactZoneBackward b = ImpactZones(independent).backward(reference, dLdz);
    EXPECT_TRUE(a.ok);
    EXPECT_LE((a.dLdx1 - b.dLdx1).cwiseAbs().maxCoeff(), 1e-10);
  }
}

TEST(CollisionImpactZones, RoundCapIsReported) {
  const MergingScene scene;
  ImpactZoneOptions o = options();
  o.independentImpacts = true;
  o.maxRounds = 1;
  const ImpactZoneResult result =
      ImpactZones(o).apply(scene.x0, scene.x1, scene.masses, listDetector(scene.candidates));
  EXPECT_TRUE(result.stats.roundCapHit);
  EXPECT_FALSE(result.stats.converged);
  EXPECT_EQ(result.stats.rounds, 2);
  EXPECT_EQ(result.stats.zones, 2);
  EXPECT_GT(result.stats.maxViolation, 0.01);  // C is left unresolved
}

TEST(CollisionImpactZones, InvalidMassesAreReported) {
  MergingScene scene;
  scene.masses[2] = 0.0;
  const ImpactZoneResult result = ImpactZones(options()).apply(scene.x0, scene.x1, scene.masses,
                                                               listDetector(scene.candidates));
  EXPECT_FALSE(result.stats.validInput);
  EXPECT_FALSE(result.stats.converged);
  EXPECT_EQ(result.positions, scene.x1);
}

// L = c . z + 1/2 |z|^2 over all nodes, through apply(), against backward().
double sceneLoss(const ImpactZones& zones, const MergingScene& scene, const NodeMatrix& x1,
                 const NodeMatrix& c, NodeMatrix* dLdz = nullptr) {
  const ImpactZoneResult r =
      zones.apply(scene.x0, x1, scene.masses, listDetector(scene.candidates));
  EXPECT_TRUE(r.stats.converged);
  if (dLdz) *dLdz = c + r.positions;
  return (c.array() * r.positions.array()).sum() + 0.5 * r.positions.squaredNorm();
}

TEST(CollisionImpactZones, BackwardMatchesCentralDifferencesThroughApply) {
  const MergingScene scene;
  const ImpactZones zones(options());
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> dist(-1.0, 1.0);
  NodeMatrix c(8, 3);
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) c(i, k) = dist(rng);
  NodeMatrix dLdz;
  sceneLoss(zones, scene, scene.x1, c, &dLdz);
  const ImpactZoneResult result =
      zones.apply(scene.x0, scene.x1, scene.masses, listDetector(scene.candidates));
  const ImpactZoneBackward qr = zones.backward(result, dLdz, ZoneGradientMethod::Qr);
  const ImpactZoneBackward kkt = zones.backward(result, dLdz, ZoneGradientMethod::Kkt);
  ASSERT_TRUE(qr.ok);
  ASSERT_TRUE(kkt.ok);
  EXPECT_LE((qr.dLdx1 - kkt.dLdx1).cwiseAbs().maxCoeff(), 1e-10);
  ASSERT_EQ(qr.dLdh.size(), 1u);

  // The fixed nodes enter only through h (h_j = thickness - sum w_k normal . x1_k), so their
  // total gradient is dL/dz (passed through) plus sum_j dL/dh_j (-w_k normal).
  NodeMatrix total = qr.dLdx1;
  const ImpactZoneRecord& zone = result.zones[0];
  for (size_t j = 0; j < zone.impacts.size(); ++j) {
    const Impact& impact = zone.impacts[j];
    for (int k = 0; k < 4; ++k)
      if (!std::isfinite(scene.masses[impact.nodes[k]]))
        total.row(impact.nodes[k]) -= qr.dLdh[0][static_cast<Eigen::Index>(j)] * impact.weights[k] *
                                      impact.normal.transpose();
  }
  const double eps = 1e-6;
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) {
      NodeMatrix plus = scene.x1, minus = scene.x1;
      plus(i, k) += eps;
      minus(i, k) -= eps;
      const double fd =
          (sceneLoss(zones, scene, plus, c) - sceneLoss(zones, scene, minus, c)) / (2 * eps);
      EXPECT_NEAR(total(i, k), fd, 1e-8) << "node " << i << " coordinate " << k;
    }
}

TEST(CollisionImpactZones, FallingSheetBackwardMatchesCentralDifferences) {
  const FallingSheet sheet;
  const ImpactZones zones(options());
  const ImpactDetector detect = floorDetector(sheet.masses, sheet.tris);
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> dist(-1.0, 1.0);
  NodeMatrix c(29, 3);
  for (int i = 0; i < 29; ++i)
    for (int k = 0; k < 3; ++k) c(i, k) = dist(rng);
  auto loss = [&](const NodeMatrix& x1) {
    return (c.array() * zones.apply(sheet.x0, x1, sheet.masses, detect).positions.array()).sum();
  };
  const ImpactZoneResult result = zones.apply(sheet.x0, sheet.x1, sheet.masses, detect);
  const ImpactZoneBackward back = zones.backward(result, c);
  ASSERT_TRUE(back.ok);
  const double eps = 1e-6;
  for (int i = 0; i < 25; ++i)  // the free nodes (the flat floor's h does not move with them)
    for (int k = 0; k < 3; ++k) {
      NodeMatrix plus = sheet.x1, minus = sheet.x1;
      plus(i, k) += eps;
      minus(i, k) -= eps;
      EXPECT_NEAR(back.dLdx1(i, k), (loss(plus) - loss(minus)) / (2 * eps), 1e-8)
          << "node " << i << " coordinate " << k;
    }
  // A node in a floor zone loses its vertical gradient; one in no zone keeps all of it.
  EXPECT_NEAR(back.dLdx1(0, 2), 0.0, 1e-15);
  EXPECT_EQ(back.dLdx1.row(22), c.row(22));
}

// Two points, a falling onto b, and two impacts of the pair whose normals nearly oppose each
// other (as two impacts of one point pair linearised at different times can): together they
// ask for (a - b)_z >= 100 thickness, a move of 0.1 m where undoing the step moves 9.5 mm.
struct ConflictingPair {
  NodeMatrix x0 = NodeMatrix::Zero(2, 3), x1 = NodeMatrix::Zero(2, 3);
  Eigen::VectorXd masses = Eigen::Vector2d(1.0, 3.0);
  std::vector<Impact> candidates;
  ConflictingPair() {
    x0(0, 2) = 0.01;
    x1(0, 2) = 0.0005;
    x1(1, 0) = 0.0002;
    // Two kinds, so that they are two pairs (a pair found again replaces its row).
    candidates.push_back(
        makeImpact(ImpactKind::VertexFace, {0, 1, -1, -1}, {1, -1, 0, 0}, Vec3(1, 0, 0.01), 0.95));
    candidates.push_back(
        makeImpact(ImpactKind::EdgeEdge, {0, 1, -1, -1}, {1, -1, 0, 0}, Vec3(-1, 0, 0.01), 0.96));
  }
  // Geometric, as the CCD is: the impacts (of `use` of the candidates) while the points are
  // closer than the thickness at the end.
  ImpactDetector detector(int use = 2) const {
    std::vector<Impact> impacts(candidates.begin(), candidates.begin() + use);
    return [impacts](const NodeMatrix&, const NodeMatrix& end) {
      return (end.row(0) - end.row(1)).norm() < kThickness ? impacts : std::vector<Impact>();
    };
  }
};

TEST(CollisionImpactZones, ZoneAskingForMoreThanUndoingTheStepMovesRigidly) {
  const ConflictingPair pair;
  const ImpactZoneResult result =
      ImpactZones(options()).apply(pair.x0, pair.x1, pair.masses, pair.detector());
  const ImpactZoneStats& s = result.stats;
  EXPECT_TRUE(s.converged);
  EXPECT_EQ(s.rigidZones, 1);
  EXPECT_EQ(s.qpFailures, 0);  // the QP converged; its answer was refused
  ASSERT_EQ(result.zones.size(), 1u);
  EXPECT_TRUE(result.zones[0].rigid);
  // x0 plus the mass-weighted mean displacement (1 (x1_a - x0_a) + 3 (x1_b - x0_b)) / 4.
  const Vec3 mean =
      (1.0 * (pair.x1.row(0) - pair.x0.row(0)) + 3.0 * (pair.x1.row(1) - pair.x0.row(1))) / 4.0;
  for (int k = 0; k < 2; ++k)
    EXPECT_LT((result.positions.row(k) - pair.x0.row(k) - mean.transpose()).norm(), 1e-15);
  EXPECT_EQ(s.maxViolation, 0.0);  // a rigid zone's rows are not its constraints
  // The same pair with one impact is an ordinary zone: the QP answer is kept.
  const ImpactZoneResult single =
      ImpactZones(options()).apply(pair.x0, pair.x1, pair.masses, pair.detector(1));
  EXPECT_EQ(single.stats.rigidZones, 0);
  EXPECT_TRUE(single.stats.converged);
}

TEST(CollisionImpactZones, RigidZoneBackwardMatchesCentralDifferences) {
  const ConflictingPair pair;
  const ImpactZones zones(options());
  const NodeMatrix c = (NodeMatrix(2, 3) << 0.3, -0.2, 0.7, -0.5, 0.1, 0.4).finished();
  auto loss = [&](const NodeMatrix& x1, NodeMatrix* dLdz) {
    const ImpactZoneResult r = zones.apply(pair.x0, x1, pair.masses, pair.detector());
    EXPECT_EQ(r.stats.rigidZones, 1);
    if (dLdz) *dLdz = c + r.positions;
    return (c.array() * r.positions.array()).sum() + 0.5 * r.positions.squaredNorm();
  };
  NodeMatrix dLdz;
  loss(pair.x1, &dLdz);
  const ImpactZoneResult r = zones.apply(pair.x0, pair.x1, pair.masses, pair.detector());
  const ImpactZoneBackward back = zones.backward(r, dLdz);
  const double eps = 1e-7;
  for (int i = 0; i < 2; ++i)
    for (int k = 0; k < 3; ++k) {
      NodeMatrix plus = pair.x1, minus = pair.x1;
      plus(i, k) += eps, minus(i, k) -= eps;
      const double fd = (loss(plus, nullptr) - loss(minus, nullptr)) / (2 * eps);
      EXPECT_NEAR(back.dLdx1(i, k), fd, 1e-7) << i << " " << k;
    }
}

}  // namespace
}  // namespace weft::collision
