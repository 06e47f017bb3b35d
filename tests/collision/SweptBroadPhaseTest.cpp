// The swept-BVH broad phase (Liang 2019 Sec. 3.3): on random small meshes, findImpacts returns
// exactly the impacts of the narrow phase run on all vertex-face and edge-edge pairs (the BVH
// loses nothing and reports each pair once), also with static obstacle vertices and after
// refitting to new positions; and the same list with 1 and 2 OpenMP threads.

#include "CollisionTestMeshes.h"

#include <weft/collision/SweptBroadPhase.h>

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <set>

namespace weft::collision {
namespace {

// Two 4 x 4 grids 0.1 apart, crumpled by noise, then each vertex displaced randomly.
struct Step {
  TriangleMesh mesh;
  NodeMatrix start, end;
};

Step randomStep(std::mt19937& rng, int n = 4, double motion = 0.15) {
  Step step;
  step.mesh = test::gridMesh(Vec3(0, 0, 0), Vec3(1.0 / n, 0, 0), Vec3(0, 1.0 / n, 0), n, n);
  step.mesh.append(
      test::gridMesh(Vec3(0.05, 0.03, 0.1), Vec3(1.0 / n, 0, 0), Vec3(0, 1.0 / n, 0), n, n));
  std::uniform_real_distribution<double> noise(-0.04, 0.04), move(-motion, motion);
  const int m = step.mesh.vertexCount();
  step.start = step.mesh.vertices;
  step.end.resize(m, 3);
  for (int i = 0; i < m; ++i)
    for (int c = 0; c < 3; ++c) {
      step.start(i, c) += noise(rng);
      step.end(i, c) = step.start(i, c) + move(rng);
    }
  return step;
}

PairPositions gather(const NodeMatrix& x, const std::array<int, 4>& nodes) {
  PairPositions p;
  for (int k = 0; k < 4; ++k) p[k] = x.row(nodes[k]).transpose();
  return p;
}

// The narrow phase on every pair, with the broad phase's node order (edge-edge: the edge with
// the lower index in buildEdges first), skipping all-static pairs.
std::vector<Impact> allPairsImpacts(const TriangleMesh& mesh, const NodeMatrix& start,
                                    const NodeMatrix& end, double thickness,
                                    const std::vector<bool>& isStatic = {}) {
  std::vector<Impact> impacts;
  auto skip = [&](const std::array<int, 4>& n) {
    return !isStatic.empty() && isStatic[n[0]] && isStatic[n[1]] && isStatic[n[2]] &&
           isStatic[n[3]];
  };
  auto run = [&](ImpactKind kind, const std::array<int, 4>& nodes) {
    if (skip(nodes)) return;
    if (auto impact = pairCcd(kind, gather(start, nodes), gather(end, nodes), thickness)) {
      impact->nodes = nodes;
      impacts.push_back(*impact);
    }
  };
  std::set<int> used;
  for (int t = 0; t < mesh.triangleCount(); ++t)
    for (int c = 0; c < 3; ++c) used.insert(mesh.triangles(t, c));
  for (int v : used)
    for (int t = 0; t < mesh.triangleCount(); ++t) {
      const auto f = mesh.triangles.row(t);
      if (f[0] != v && f[1] != v && f[2] != v) run(ImpactKind::VertexFace, {v, f[0], f[1], f[2]});
    }
  const std::vector<MeshEdge> edges = buildEdges(mesh);
  for (std::size_t i = 0; i < edges.size(); ++i)
    for (std::size_t j = i + 1; j < edges.size(); ++j) {
      const MeshEdge &a = edges[i], &b = edges[j];
      if (a.a == b.a || a.a == b.b || a.b == b.a || a.b == b.b) continue;
      run(ImpactKind::EdgeEdge, {a.a, a.b, b.a, b.b});
    }
  std::sort(impacts.begin(), impacts.end(), impactLess);
  return impacts;
}

void expectSameImpacts(const std::vector<Impact>& a, const std::vector<Impact>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].kind, b[i].kind);
    EXPECT_EQ(a[i].nodes, b[i].nodes);
    EXPECT_EQ(a[i].time, b[i].time);
    EXPECT_EQ(a[i].weights, b[i].weights);
    EXPECT_EQ(a[i].normal, b[i].normal);
  }
}

TEST(CollisionBroadPhase, FindsExactlyTheAllPairsImpacts) {
  std::mt19937 rng(21);
  int total = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const Step step = randomStep(rng);
    const double thickness = trial % 2 ? 1e-3 : 0.02;
    SweptBroadPhase broad(step.mesh);
    const std::vector<Impact> found = broad.findImpacts(step.start, step.end, thickness);
    const std::vector<Impact> truth = allPairsImpacts(step.mesh, step.start, step.end, thickness);
    expectSameImpacts(found, truth);
    // Candidates: each pair once, never sharing a vertex.
    const std::vector<CcdCandidate>& candidates =
        broad.findCandidates(step.start, step.end, thickness);
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      const auto& n = candidates[i].nodes;
      if (candidates[i].kind == ImpactKind::VertexFace)
        EXPECT_TRUE(n[0] != n[1] && n[0] != n[2] && n[0] != n[3]);
      else
        EXPECT_TRUE(n[0] != n[2] && n[0] != n[3] && n[1] != n[2] && n[1] != n[3]);
      if (i > 0) {
        EXPECT_TRUE(candidates[i - 1].kind != candidates[i].kind ||
                    candidates[i - 1].nodes != candidates[i].nodes);
      }
    }
    total += static_cast<int>(found.size());
  }
  std::printf("all-pairs agreement: %d impacts over 12 random steps\n", total);
  EXPECT_GT(total, 100);
}

TEST(CollisionBroadPhase, PrunesMostPairs) {
  // A 16 x 16 cloth moving a little: far fewer candidates than pairs, the impacts unchanged.
  std::mt19937 rng(22);
  TriangleMesh mesh =
      test::gridMesh(Vec3(0, 0, 0), Vec3(1.0 / 16, 0, 0), Vec3(0, 1.0 / 16, 0), 16, 16);
  NodeMatrix start = mesh.vertices, end = mesh.vertices;
  std::uniform_real_distribution<double> noise(-0.02, 0.02);
  for (int i = 0; i < mesh.vertexCount(); ++i) {
    start(i, 2) = noise(rng);
    end.row(i) = start.row(i) + Vec3(noise(rng), noise(rng), 4 * noise(rng)).transpose();
  }
  SweptBroadPhase broad(mesh);
  const std::size_t candidates = broad.findCandidates(start, end, 1e-3).size();
  const double edges = static_cast<double>(broad.edges().size());
  const double pairs = static_cast<double>(mesh.vertexCount()) * mesh.triangleCount() +
                       0.5 * edges * edges;  // about all vertex-face and edge-edge pairs
  std::printf("candidates %zu of about %.0f pairs\n", candidates, pairs);
  EXPECT_LT(static_cast<double>(candidates), 0.05 * pairs);
  expectSameImpacts(broad.findImpacts(start, end, 1e-3), allPairsImpacts(mesh, start, end, 1e-3));
}

TEST(CollisionBroadPhase, StaticObstacleVerticesAreNotTestedAmongThemselves) {
  std::mt19937 rng(23);
  for (int trial = 0; trial < 6; ++trial) {
    const Step step = randomStep(rng);
    // The first grid is the obstacle: static flags, and it does not move.
    const int half = step.mesh.vertexCount() / 2;
    std::vector<bool> isStatic(step.mesh.vertexCount(), false);
    std::fill(isStatic.begin(), isStatic.begin() + half, true);
    NodeMatrix end = step.end;
    end.topRows(half) = step.start.topRows(half);
    SweptBroadPhase broad(step.mesh, isStatic);
    for (const CcdCandidate& c : broad.findCandidates(step.start, end, 0.02))
      EXPECT_FALSE(isStatic[c.nodes[0]] && isStatic[c.nodes[1]] && isStatic[c.nodes[2]] &&
                   isStatic[c.nodes[3]]);
    const std::vector<Impact> found = broad.findImpacts(step.start, end, 0.02);
    expectSameImpacts(found, allPairsImpacts(step.mesh, step.start, end, 0.02, isStatic));
    // Obstacle-cloth impacts are kept.
    EXPECT_TRUE(std::any_of(found.begin(), found.end(), [&](const Impact& i) {
      return std::any_of(i.nodes.begin(), i.nodes.end(), [&](int n) { return isStatic[n]; });
    }));
  }
}

TEST(CollisionBroadPhase, RefitsToNewPositions) {
  // One broad phase reused over several steps gives what a fresh one gives.
  std::mt19937 rng(24);
  const Step first = randomStep(rng);
  SweptBroadPhase reused(first.mesh);
  for (int trial = 0; trial < 4; ++trial) {
    const Step step = randomStep(rng, 4, 0.05 + 0.05 * trial);
    SweptBroadPhase fresh(step.mesh);
    expectSameImpacts(reused.findImpacts(step.start, step.end, 0.01),
                      fresh.findImpacts(step.start, step.end, 0.01));
  }
}

TEST(CollisionBroadPhase, SameImpactsWithOneAndTwoThreads) {
  std::mt19937 rng(25);
  const Step step = randomStep(rng, 12, 0.05);
  SweptBroadPhase broad(step.mesh);
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const std::vector<Impact> one = broad.findImpacts(step.start, step.end, 0.01);
  omp_set_num_threads(2);
  const std::vector<Impact> two = broad.findImpacts(step.start, step.end, 0.01);
  SweptBroadPhase other(step.mesh);
  const std::vector<Impact> twoFresh = other.findImpacts(step.start, step.end, 0.01);
  omp_set_num_threads(saved);
  std::printf("thread determinism: %zu impacts from %zu candidates\n", one.size(),
              broad.findCandidates(step.start, step.end, 0.01).size());
  EXPECT_GT(one.size(), 50u);
  expectSameImpacts(one, two);
  expectSameImpacts(one, twoFresh);
  EXPECT_TRUE(std::is_sorted(one.begin(), one.end(), impactLess));
}

}  // namespace
}  // namespace weft::collision
