#pragma once
// Collision response by non-rigid impact zones (Liang et al. 2019 Sec. 3.4, after Bridson et
// al. 2002, Harmon et al. 2008 and ARCSim): move the candidate end positions x1 of a step as
// little as possible, in the mass-weighted norm, so that no impact (Impact.h) remains closer
// than the thickness.
//
// Rounds: detect impacts from x0 to the current positions; keep them all, or with
// ImpactZoneOptions::independentImpacts only independent ones (ARCSim: sorted by time, an impact
// sharing a free node with an earlier kept one is dropped, since once the earlier one moves the
// shared node the later one's time, weights and normal are stale; it is found again next round
// if it persists); merge each kept impact with the zones holding its free nodes (union-find);
// re-solve every zone that grew, as one QP over all the impacts accumulated in it (ZoneQp.h, or
// SparseZoneQp.h for large zones), from the candidate positions x1; repeat until the detector
// finds nothing or the round cap (reported).
//
// Unlike ARCSim, whose zone solve starts from the current (already projected) positions, each
// zone's QP targets x1: the final positions of a zone are then one QP of x1 restricted to its
// nodes, the minimum mass-weighted displacement satisfying all its impacts, and the backward
// pass is exact through that single QP (with G, h held fixed).
//
// The failsafe (Bridson et al. 2002, Harmon et al. 2008: rigid impact zones): a zone whose QP
// does not converge, whose answer moves it much farther than undoing the step would (more than
// twice as far plus the thickness, root-mean-square over the zone's mass or at its farthest
// node: the linearised constraints, taken at different times of the step, disagree with each
// other), or that still
// grows after rigidAfterRounds rounds, moves rigidly instead: its nodes go to x0 plus the zone's
// mass-weighted mean displacement x1 - x0 (momentum kept, rotation not). x0 is collision-free, so a
// translated zone is too within itself; a rigid zone that merges with another stays rigid.
//
// Fixed nodes (infinite mass: obstacles, pinned nodes) do not move and are not QP variables:
// their columns are excluded and their term -w_k normal . x1_k goes into h, so an impact row is
// G = -w_k normal^T at each free node k and h = thickness - sum_fixed w_k normal . x1_k. They
// never link zones (a floor touched by many nodes does not make them one zone). W is the free
// nodes' masses over the zone's mean mass, per coordinate (the scale of W changes lambda, not z
// nor the gradients).

#include <weft/collision/Impact.h>
#include <weft/collision/SparseZoneQp.h>
#include <weft/collision/ZoneQp.h>
#include <weft/core/Types.h>

#include <functional>
#include <vector>

namespace weft::collision {

// Impacts of the motion from start to end (m x 3 each); normal . s(end) < thickness for each.
using ImpactDetector =
    std::function<std::vector<Impact>(const NodeMatrix& start, const NodeMatrix& end)>;

struct ImpactZoneOptions {
  double thickness = 1e-4;  // delta: each impact's constraint is normal . s(z) >= thickness
  int maxRounds = 100;      // detection rounds before giving up (reported, not silent)
  // Zones with more impact constraints than this are solved sparsely (SparseZoneQp.h).
  int denseLimit = 48;
  // A sparse solve that stops short of the tolerance is redone densely when G has at most this
  // many entries (m x n).
  double denseFallbackEntries = 4e6;
  // Keep only independent impacts per round (ARCSim: one sharing a free node with an earlier
  // one waits for the next round). Off by default: every impact of a round is a linear
  // constraint of the re-solved zone, and cloth layers resting on each other give hundreds of
  // impacts sharing nodes, which the rule would spread over as many rounds.
  bool independentImpacts = false;
  // Rounds after which a zone that grows again is made rigid (see the failsafe above).
  int rigidAfterRounds = 20;
  ZoneQpOptions qp;
};

// One zone at the end of apply(): what its backward pass needs.
struct ImpactZoneRecord {
  std::vector<int> nodes;       // free nodes, ascending; QP coordinate 3 i + c is nodes[i], c
  std::vector<Impact> impacts;  // row j of qp.G / qp.h is impacts[j]
  ZoneQp qp;                    // x = x1 at nodes, W, G, h as solved (small zones)
  bool sparse = false;          // large zone: solved as sparseQp, qp left empty
  SparseZoneQp sparseQp;
  ZoneQpSolution solution;     // z, lambda of the last solve
  bool rigid = false;          // moved by the failsafe's translation; qp, solution not used
  std::vector<double> masses;  // of nodes (the rigid translation's weights)
};

struct ImpactZoneStats {
  int rounds = 0;                  // detection rounds run (including the last, empty one)
  int zones = 0;                   // zones at the end
  int constraints = 0;             // impact rows over all final zones
  int impactsDetected = 0;         // over all rounds
  int impactsKept = 0;             // impacts added to zones, over all rounds
  int impactsWithoutFreeNode = 0;  // detected impacts between fixed nodes only (ignored)
  int rigidZones = 0;              // final zones moved by the failsafe's translation
  int qpSolves = 0;
  long qpIterationsTotal = 0;
  int qpIterationsMax = 0;
  bool allQpConverged = true;
  bool roundCapHit = false;
  int qpFailures = 0;      // QP solves that did not converge (their zones were made rigid)
  bool validInput = true;  // false: x0, x1, masses disagree in size or a mass is not > 0
  bool converged = false;  // the detector found nothing: the step is collision-free
  // Largest remaining violation, max(0, thickness - normal . s(z)), over the final non-rigid
  // zones' impacts and (when the round cap was hit) the last round's detected impacts.
  double maxViolation = 0.0;
};

struct ImpactZoneResult {
  NodeMatrix positions;  // m x 3: z, the response
  ImpactZoneStats stats;
  std::vector<ImpactZoneRecord> zones;
};

enum class ZoneGradientMethod { Qr, Kkt };

struct ImpactZoneBackward {
  NodeMatrix dLdx1;  // m x 3
  // Per final zone (same order as ImpactZoneResult::zones): dL/dG (rows x 3 nodes) and dL/dh,
  // for the caller to chain to the impacts' normals, weights and the fixed nodes' positions.
  std::vector<Eigen::MatrixXd> dLdG;
  std::vector<Eigen::VectorXd> dLdh;
  bool ok = true;  // every zone's gradient was computed (KKT can be singular)
};

class ImpactZones {
 public:
  explicit ImpactZones(const ImpactZoneOptions& options = {}) : options_(options) {}
  const ImpactZoneOptions& options() const { return options_; }

  // masses: one per node, > 0; +infinity marks a fixed node. Invalid input returns x1 with
  // stats.validInput = false and nothing detected.
  ImpactZoneResult apply(const NodeMatrix& x0, const NodeMatrix& x1, const Eigen::VectorXd& masses,
                         const ImpactDetector& detect) const;

  // dL/dx1 from dL/dz through every final zone's QP with its G and h held fixed (treated as
  // constants of the step), or through a rigid zone's mean displacement; nodes in no zone, fixed
  // ones included, pass dL/dz through.
  ImpactZoneBackward backward(const ImpactZoneResult& result, const NodeMatrix& dLdz,
                              ZoneGradientMethod method = ZoneGradientMethod::Qr) const;

 private:
  ImpactZoneOptions options_;
};

}  // namespace weft::collision
