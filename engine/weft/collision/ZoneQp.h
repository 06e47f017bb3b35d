#pragma once
// One impact zone's quadratic program and its gradients (Liang et al. 2019 Sec. 3.4):
//   minimise 1/2 (z - x)^T W (z - x)  subject to  G z + h <= 0          (Liang Eqs. 8-9)
// W diagonal positive (one weight per coordinate, n = 3 x zone nodes), G dense m x n (zones are
// small), h an m-vector. The Lagrangian is 1/2 |z - x|_W^2 + lambda^T (G z + h), so at the
// optimum W (z - x) + G^T lambda = 0 (Liang Eq. 10), lambda >= 0, lambda_j (G z + h)_j = 0.
//
// The forward solve is the Goldfarb-Idnani dual active-set method in the variables
// y = W^{1/2} z (Hessian I): start from the unconstrained minimiser z = x, add the most violated
// constraint, drop an active constraint whose multiplier would turn negative. Its active set
// stays linearly independent, so duplicated or dependent rows of G are handled; a constraint
// that no step can satisfy proves the QP infeasible. Exact in finitely many steps, which suits
// small dense strictly convex QPs.
//
// The backward pass maps dL/dz to dL/dx, dL/dG, dL/dh, either by the QR route of Liang
// Sec. 3.4.1-3.4.2 (Eqs. 17-21) or by the full (n + m) KKT system of Liang Eq. 13 (the ablation
// of Liang Table 1, and the tests' oracle). Both take the same inputs so they can be timed on
// the same zone.

#include <Eigen/Core>

#include <vector>

namespace weft::collision {

struct ZoneQp {
  Eigen::VectorXd x;        // n: the unconstrained minimiser (target positions)
  Eigen::VectorXd weights;  // n: the diagonal of W, every entry > 0
  Eigen::MatrixXd G;        // m x n
  Eigen::VectorXd h;        // m
};

struct ZoneQpOptions {
  // Constraint j counts as satisfied when (G z + h)_j <= violationTolerance * scale_j, with
  // scale_j = |h_j| + sum_k |G_jk z_k|: relative to the terms summed, so the test is above
  // round-off whatever the thickness (a thickness-relative test cannot be met when h is tiny).
  double violationTolerance = 1e-12;
  // A new constraint's direction counts as in the span of the active ones when its component
  // outside that span is below dependenceTolerance times its norm (Goldfarb-Idnani's z = 0).
  double dependenceTolerance = 1e-10;
  // Steps (additions and drops) before giving up; <= 0 means 10 (m + n) + 10. Hitting it is
  // reported (stop = IterationCap, converged = false), never silent.
  int maxIterations = 0;
};

enum class ZoneQpStop {
  Optimal,       // every constraint satisfied to tolerance, KKT hold
  Infeasible,    // a violated constraint is a nonpositive combination of the active ones
  IterationCap,  // maxIterations steps taken without reaching the optimum
  InvalidInput,  // sizes disagree, a weight is not positive, or a value is not finite
};
const char* toString(ZoneQpStop stop);

struct ZoneQpSolution {
  Eigen::VectorXd z;           // n: the minimiser (at a stop other than Optimal: the last iterate)
  Eigen::VectorXd lambda;      // m: multipliers, >= 0, zero off the active set
  std::vector<int> activeSet;  // the final active set: linearly independent rows of G
  int iterations = 0;          // Goldfarb-Idnani steps taken (additions and drops)
  bool converged = false;      // stop == Optimal
  double maxViolation = 0.0;   // max(0, max_j (G z + h)_j), absolute
  ZoneQpStop stop = ZoneQpStop::InvalidInput;
};

ZoneQpSolution solveZoneQp(const ZoneQp& qp, const ZoneQpOptions& options = {});

struct ZoneQpGradientOptions {
  // Rows kept for the gradient: lambda_j > lambdaThreshold (see zoneQpGradientQr).
  double lambdaThreshold = 0.0;
  // QR rank test: R_kk is dropped when |R_kk| < rankTolerance |R_00| (Liang Sec. 3.4.2 truncates
  // at |R_kk| < 1e-6 with unit-scale rows; relative here so that the test does not depend on W's
  // scale).
  double rankTolerance = 1e-6;
};

struct ZoneQpGradient {
  Eigen::VectorXd dLdx;           // n
  Eigen::MatrixXd dLdG;           // m x n
  Eigen::VectorXd dLdh;           // m
  Eigen::VectorXd dz;             // n: d_z of Liang Eq. 13 / Eq. 18
  Eigen::VectorXd lambdaDLambda;  // m: D(lambda) d_lambda of Liang Eq. 13 / Eq. 19
  Eigen::VectorXd lambdaUsed;     // m: lambda after the transfer of Liang Eq. 21 (QR route)
  int activeConstraints = 0;      // rows entering the linear algebra
  int rank = 0;                   // numerical rank of those rows (QR) or of the KKT matrix
  bool ok = false;  // false: invalid sizes, or (KKT route) the Eq. 13 matrix is singular
};

// Liang Sec. 3.4.1-3.4.2: QR of W^{-1/2} G_A^T over the rows with lambda_j > 0, truncated at
// the numerical rank with the multipliers of the dropped rows moved onto the kept ones (Eq. 21),
// then d_z = W^{-1/2} (I - Q Q^T) W^{-1/2} dL/dz (Eq. 18), D(lambda) d_lambda = R^{-1} Q^T
// W^{-1/2} dL/dz (Eq. 19), dL/dx = W d_z, dL/dG = -D(lambda) d_lambda z^T - lambda d_z^T,
// dL/dh = -D(lambda) d_lambda (Eqs. 14-16).
ZoneQpGradient zoneQpGradientQr(const ZoneQp& qp, const ZoneQpSolution& solution,
                                const Eigen::VectorXd& dLdz,
                                const ZoneQpGradientOptions& options = {});

// The same gradient from the full (n + m) system of Liang Eq. 13 over every row of G, by dense
// LU with full pivoting. Singular (ok = false) when a row is tight with lambda_j = 0 or the
// active rows are linearly dependent; then use the QR route.
ZoneQpGradient zoneQpGradientKkt(const ZoneQp& qp, const ZoneQpSolution& solution,
                                 const Eigen::VectorXd& dLdz);

}  // namespace weft::collision
