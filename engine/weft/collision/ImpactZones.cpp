#include <weft/collision/ImpactZones.h>

#include <algorithm>
#include <cmath>

namespace weft::collision {

namespace {

bool isFixed(const Eigen::VectorXd& masses, int node) {
  return !std::isfinite(masses[node]);
}

bool hasFreeNode(const Impact& impact, const Eigen::VectorXd& masses) {
  for (int k = 0; k < 4; ++k) {
    const int node = impact.nodes[static_cast<size_t>(k)];
    if (node >= 0 && impact.weights[static_cast<size_t>(k)] != 0.0 && !isFixed(masses, node))
      return true;
  }
  return false;
}

// thickness - normal . s(x): positive when the impact's constraint is violated.
double violation(const Impact& impact, const NodeMatrix& x, double thickness) {
  Vec3 s = Vec3::Zero();
  for (int k = 0; k < 4; ++k) {
    const int node = impact.nodes[static_cast<size_t>(k)];
    if (node >= 0) s += impact.weights[static_cast<size_t>(k)] * x.row(node).transpose();
  }
  return thickness - impact.normal.dot(s);
}

struct Zone {
  std::vector<int> nodes;  // free nodes
  std::vector<Impact> impacts;
  bool dirty = false;  // grew this round: its QP must be solved again
  bool alive = true;
  bool rigid = false;  // the failsafe: translated with the mean displacement
  ZoneQp qp;
  bool sparse = false;
  SparseZoneQp sparseQp;
  ZoneQpSolution solution;
};

// Liang Eqs. 8-9 for one zone: x = x1 at its free nodes, W = mass / mean mass per coordinate,
// one row per impact, G = -w_k normal^T at free node k, h = thickness - sum over fixed nodes of
// w_k normal . x1_k. localOf maps a node to its position in zone.nodes (-1 elsewhere).
void buildZoneQp(Zone& zone, const NodeMatrix& x1, const Eigen::VectorXd& masses, double thickness,
                 int denseLimit, std::vector<int>& localOf) {
  std::sort(zone.nodes.begin(), zone.nodes.end());
  const Eigen::Index count = static_cast<Eigen::Index>(zone.nodes.size());
  const Eigen::Index n = 3 * count;
  const Eigen::Index m = static_cast<Eigen::Index>(zone.impacts.size());
  ZoneQp& qp = zone.qp;
  qp.x.resize(n);
  qp.weights.resize(n);
  double meanMass = 0.0;
  for (int node : zone.nodes) meanMass += masses[node];
  meanMass /= static_cast<double>(std::max<Eigen::Index>(count, 1));
  for (Eigen::Index i = 0; i < count; ++i) {
    const int node = zone.nodes[static_cast<size_t>(i)];
    localOf[static_cast<size_t>(node)] = static_cast<int>(i);
    qp.x.segment<3>(3 * i) = x1.row(node).transpose();
    qp.weights.segment<3>(3 * i).setConstant(masses[node] / meanMass);
  }
  zone.sparse = m > denseLimit;
  std::vector<Eigen::Triplet<double>> triplets;
  if (zone.sparse) {
    triplets.reserve(static_cast<size_t>(12 * m));
    qp.G.resize(0, 0);
  } else {
    qp.G.setZero(m, n);
  }
  qp.h.resize(m);
  for (Eigen::Index j = 0; j < m; ++j) {
    const Impact& impact = zone.impacts[static_cast<size_t>(j)];
    qp.h[j] = thickness;
    for (int k = 0; k < 4; ++k) {
      const int node = impact.nodes[static_cast<size_t>(k)];
      const double w = impact.weights[static_cast<size_t>(k)];
      if (node < 0 || w == 0.0) continue;
      if (isFixed(masses, node)) {
        qp.h[j] -= w * impact.normal.dot(x1.row(node).transpose());
      } else {
        const int local = localOf[static_cast<size_t>(node)];
        if (zone.sparse)
          for (int c = 0; c < 3; ++c)
            triplets.emplace_back(j, 3 * local + c, -w * impact.normal[c]);
        else
          qp.G.block<1, 3>(j, 3 * local) -= w * impact.normal.transpose();
      }
    }
  }
  for (int node : zone.nodes) localOf[static_cast<size_t>(node)] = -1;
  if (zone.sparse) {
    SparseZoneQp& sq = zone.sparseQp;
    sq.x = std::move(qp.x);
    sq.weights = std::move(qp.weights);
    sq.h = std::move(qp.h);
    sq.G.resize(m, n);
    sq.G.setFromTriplets(triplets.begin(), triplets.end());  // (duplicates summed)
    qp = ZoneQp();
  }
}

// The failsafe's test (ImpactZones.h): a zone's QP answer is refused when its move, root-mean-
// square over the zone's mass or the largest of any node, exceeds this many times that of
// undoing the step, plus the thickness. A consistent zone moves less than undoing would (resting
// layers: about as much, since each step's sag is pushed back); zones whose linearised rows
// disagree asked for 3.5 to 170 times as much in the stacked cloths of
// docs/how-it-works/collision.md.
constexpr double kUndoFactor = 2.0;

// The failsafe's rigid response: x0 plus the zone's mass-weighted mean displacement.
void translateRigidly(const std::vector<int>& nodes, const Eigen::VectorXd& masses,
                      const NodeMatrix& x0, const NodeMatrix& x1, NodeMatrix& positions) {
  Vec3 momentum = Vec3::Zero();
  double mass = 0.0;
  for (int node : nodes) {
    momentum += masses[node] * (x1.row(node) - x0.row(node)).transpose();
    mass += masses[node];
  }
  const Vec3 mean = momentum / mass;
  for (int node : nodes) positions.row(node) = x0.row(node) + mean.transpose();
}

}  // namespace

ImpactZoneResult ImpactZones::apply(const NodeMatrix& x0, const NodeMatrix& x1,
                                    const Eigen::VectorXd& masses,
                                    const ImpactDetector& detect) const {
  const int m = static_cast<int>(x1.rows());
  ImpactZoneResult result;
  result.positions = x1;
  ImpactZoneStats& stats = result.stats;
  if (x0.rows() != x1.rows() || masses.size() != x1.rows() || (masses.array() <= 0.0).any() ||
      masses.hasNaN()) {
    stats.validInput = false;
    stats.allQpConverged = false;
    return result;
  }
  std::vector<Zone> zones;
  std::vector<int> zoneOf(static_cast<size_t>(m), -1);
  std::vector<int> localOf(static_cast<size_t>(m), -1);
  std::vector<char> claimed(static_cast<size_t>(m), 0);
  std::vector<Impact> kept;
  std::vector<int> touching;
  bool clean = false;

  for (int round = 0;; ++round) {
    std::vector<Impact> impacts = detect(x0, result.positions);
    ++stats.rounds;
    stats.impactsDetected += static_cast<int>(impacts.size());
    // Impacts between fixed nodes only cannot be resolved by moving anything: counted, ignored.
    const auto fixedOnly = std::remove_if(impacts.begin(), impacts.end(),
                                          [&](const Impact& i) { return !hasFreeNode(i, masses); });
    stats.impactsWithoutFreeNode += static_cast<int>(impacts.end() - fixedOnly);
    impacts.erase(fixedOnly, impacts.end());
    if (impacts.empty()) {
      clean = true;
      break;
    }
    if (round == options_.maxRounds) {
      stats.roundCapHit = true;
      for (const Impact& impact : impacts)
        stats.maxViolation =
            std::max(stats.maxViolation, violation(impact, result.positions, options_.thickness));
      break;
    }

    // Independent impacts: earliest first; one sharing a free node with a kept one waits.
    std::stable_sort(impacts.begin(), impacts.end(),
                     [](const Impact& a, const Impact& b) { return a.time < b.time; });
    kept.clear();
    std::fill(claimed.begin(), claimed.end(), 0);
    for (const Impact& impact : impacts) {
      if (!options_.independentImpacts) {
        kept.push_back(impact);
        continue;
      }
      bool shares = false;
      for (int k = 0; k < 4; ++k) {
        const int node = impact.nodes[static_cast<size_t>(k)];
        if (node >= 0 && !isFixed(masses, node) && claimed[static_cast<size_t>(node)])
          shares = true;
      }
      if (shares) continue;
      for (int node : impact.nodes)
        if (node >= 0 && !isFixed(masses, node)) claimed[static_cast<size_t>(node)] = 1;
      kept.push_back(impact);
    }
    stats.impactsKept += static_cast<int>(kept.size());

    // Union-find over free nodes: the impact joins (and merges) the zones of its free nodes.
    for (const Impact& impact : kept) {
      touching.clear();
      for (int node : impact.nodes)
        if (node >= 0 && !isFixed(masses, node) && zoneOf[static_cast<size_t>(node)] >= 0)
          touching.push_back(zoneOf[static_cast<size_t>(node)]);
      std::sort(touching.begin(), touching.end());
      touching.erase(std::unique(touching.begin(), touching.end()), touching.end());
      int target;
      if (touching.empty()) {
        target = static_cast<int>(zones.size());
        zones.emplace_back();
      } else {
        // Merge into the largest touching zone, relabelling the others' nodes.
        target = *std::max_element(touching.begin(), touching.end(), [&](int a, int b) {
          return zones[static_cast<size_t>(a)].nodes.size() <
                 zones[static_cast<size_t>(b)].nodes.size();
        });
        for (int other : touching) {
          if (other == target) continue;
          Zone& from = zones[static_cast<size_t>(other)];
          Zone& to = zones[static_cast<size_t>(target)];
          for (int node : from.nodes) zoneOf[static_cast<size_t>(node)] = target;
          to.nodes.insert(to.nodes.end(), from.nodes.begin(), from.nodes.end());
          to.impacts.insert(to.impacts.end(), from.impacts.begin(), from.impacts.end());
          to.rigid = to.rigid || from.rigid;
          from = Zone();
          from.alive = false;
        }
      }
      Zone& zone = zones[static_cast<size_t>(target)];
      for (int k = 0; k < 4; ++k) {
        const int node = impact.nodes[static_cast<size_t>(k)];
        if (node < 0 || isFixed(masses, node) || zoneOf[static_cast<size_t>(node)] == target)
          continue;
        zoneOf[static_cast<size_t>(node)] = target;
        zone.nodes.push_back(node);
      }
      // A pair found again (the response left it closer than the thickness, or its path still
      // meets) replaces its older row: the new one is linearised on the current trajectory, and
      // stacking both would grow the zone by a row per round for every resting pair.
      const auto same =
          std::find_if(zone.impacts.begin(), zone.impacts.end(), [&](const Impact& other) {
            return other.kind == impact.kind && other.nodes == impact.nodes;
          });
      if (same != zone.impacts.end())
        *same = impact;
      else
        zone.impacts.push_back(impact);
      zone.dirty = true;
    }

    // Re-solve the zones that grew, from x1, over all their impacts.
    for (Zone& zone : zones) {
      if (!zone.alive || !zone.dirty) continue;
      zone.dirty = false;
      if (round >= options_.rigidAfterRounds) zone.rigid = true;
      if (zone.rigid) {
        translateRigidly(zone.nodes, masses, x0, x1, result.positions);
        continue;
      }
      buildZoneQp(zone, x1, masses, options_.thickness, options_.denseLimit, localOf);
      zone.solution = zone.sparse ? solveSparseZoneQp(zone.sparseQp, options_.qp)
                                  : solveZoneQp(zone.qp, options_.qp);
      if (zone.sparse && !zone.solution.converged &&
          static_cast<double>(zone.impacts.size()) * static_cast<double>(3 * zone.nodes.size()) <=
              options_.denseFallbackEntries) {
        // The augmented Lagrangian can stall at round-off short of the tolerance; the exact
        // dense method settles it where G still fits in memory.
        zone.qp = toDense(zone.sparseQp);
        zone.sparse = false;
        zone.sparseQp = SparseZoneQp();
        const int sparseSteps = zone.solution.iterations;
        zone.solution = solveZoneQp(zone.qp, options_.qp);
        zone.solution.iterations += sparseSteps;
      }
      ++stats.qpSolves;
      stats.qpIterationsTotal += zone.solution.iterations;
      stats.qpIterationsMax = std::max(stats.qpIterationsMax, zone.solution.iterations);
      if (!zone.solution.converged) ++stats.qpFailures, stats.allQpConverged = false;
      bool accept = zone.solution.converged;
      if (accept) {
        // The QP's move against undoing the step: root-mean-square over the zone's mass, and
        // the largest of any node.
        double moved = 0.0, undone = 0.0, mass = 0.0, movedMax = 0.0, undoneMax = 0.0;
        for (size_t i = 0; i < zone.nodes.size(); ++i) {
          const int node = zone.nodes[i];
          const double move =
              (zone.solution.z.segment<3>(3 * static_cast<Eigen::Index>(i)).transpose() -
               x1.row(node))
                  .norm();
          const double undo = (x0.row(node) - x1.row(node)).norm();
          moved += masses[node] * move * move, undone += masses[node] * undo * undo;
          mass += masses[node];
          movedMax = std::max(movedMax, move), undoneMax = std::max(undoneMax, undo);
        }
        accept = std::sqrt(moved / mass) <=
                     kUndoFactor * std::sqrt(undone / mass) + options_.thickness &&
                 movedMax <= kUndoFactor * undoneMax + options_.thickness;
      }
      if (!accept) {
        zone.rigid = true;
        translateRigidly(zone.nodes, masses, x0, x1, result.positions);
        continue;
      }
      for (size_t i = 0; i < zone.nodes.size(); ++i)
        result.positions.row(zone.nodes[i]) =
            zone.solution.z.segment<3>(3 * static_cast<Eigen::Index>(i)).transpose();
    }
  }

  for (Zone& zone : zones) {
    if (!zone.alive) continue;
    if (zone.rigid) ++stats.rigidZones;
    // A rigid zone's rows are not its constraints: the detector's verdict (clean or the round
    // cap) speaks for it.
    for (const Impact& impact : zone.rigid ? std::vector<Impact>() : zone.impacts)
      stats.maxViolation =
          std::max(stats.maxViolation, violation(impact, result.positions, options_.thickness));
    stats.constraints += static_cast<int>(zone.impacts.size());
    ImpactZoneRecord record;
    record.nodes = std::move(zone.nodes);
    record.impacts = std::move(zone.impacts);
    record.qp = std::move(zone.qp);
    record.sparse = zone.sparse;
    record.sparseQp = std::move(zone.sparseQp);
    record.solution = std::move(zone.solution);
    record.rigid = zone.rigid;
    for (int node : record.nodes) record.masses.push_back(masses[node]);
    result.zones.push_back(std::move(record));
  }
  stats.zones = static_cast<int>(result.zones.size());
  stats.converged = clean;
  return result;
}

ImpactZoneBackward ImpactZones::backward(const ImpactZoneResult& result, const NodeMatrix& dLdz,
                                         ZoneGradientMethod method) const {
  ImpactZoneBackward out;
  out.dLdx1 = dLdz;
  Eigen::VectorXd g;
  for (const ImpactZoneRecord& zone : result.zones) {
    const Eigen::Index count = static_cast<Eigen::Index>(zone.nodes.size());
    if (zone.rigid) {
      // z_k = x0_k + sum_i m_i (x1_i - x0_i) / M: dL/dx1_i = m_i / M sum_k dL/dz_k.
      Vec3 total = Vec3::Zero();
      double mass = 0.0;
      for (size_t i = 0; i < zone.nodes.size(); ++i)
        total += dLdz.row(zone.nodes[i]).transpose(), mass += zone.masses[i];
      for (size_t i = 0; i < zone.nodes.size(); ++i)
        out.dLdx1.row(zone.nodes[i]) = (zone.masses[i] / mass) * total.transpose();
      out.dLdG.emplace_back();
      out.dLdh.emplace_back();
      continue;
    }
    if (!zone.solution.converged) {
      // Its nodes were left at x1: the map is the identity there.
      out.ok = false;
      const Eigen::Index rows = static_cast<Eigen::Index>(zone.impacts.size());
      out.dLdG.push_back(Eigen::MatrixXd::Zero(rows, 3 * count));
      out.dLdh.push_back(Eigen::VectorXd::Zero(rows));
      continue;
    }
    g.resize(3 * count);
    for (Eigen::Index i = 0; i < count; ++i)
      g.segment<3>(3 * i) = dLdz.row(zone.nodes[static_cast<size_t>(i)]).transpose();
    const ZoneQp dense = zone.sparse ? toDense(zone.sparseQp) : ZoneQp();
    const ZoneQp& qp = zone.sparse ? dense : zone.qp;
    const ZoneQpGradient grad = method == ZoneGradientMethod::Qr
                                    ? zoneQpGradientQr(qp, zone.solution, g)
                                    : zoneQpGradientKkt(qp, zone.solution, g);
    if (!grad.ok) out.ok = false;
    for (Eigen::Index i = 0; i < count; ++i)
      out.dLdx1.row(zone.nodes[static_cast<size_t>(i)]) = grad.dLdx.segment<3>(3 * i).transpose();
    out.dLdG.push_back(grad.dLdG);
    out.dLdh.push_back(grad.dLdh);
  }
  return out;
}

}  // namespace weft::collision
