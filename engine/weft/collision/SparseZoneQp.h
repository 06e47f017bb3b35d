#pragma once
// The impact-zone QP of ZoneQp.h (Liang 2019 Eqs. 8-9) for large zones, where G is sparse: each
// row touches the 4 nodes of one impact. Cloth layers resting on each other make zones of
// thousands of constraints, where the dense Goldfarb-Idnani method (a QR of the active set per
// step) costs O(n m^3).
//
// Solved by the augmented Lagrangian method (as ARCSim solves zones, Liang 2019 Sec. 3.4), with
// exact inner solves: for multipliers lambda and a penalty rho, minimise
//   1/2 |z - x|_W^2 + rho/2 sum_j max(0, g_j(z) + lambda_j / rho)^2,   g(z) = G z + h,
// a strictly convex piecewise quadratic, by semismooth Newton steps on its active rows A:
// (W + rho G_A^T G_A) z = W x - G_A^T (lambda_A + rho h_A), one sparse LDL^T each, well posed
// whatever the rank of G (rows of cloth layers depend on each other, which makes the dual's
// matrix G W^-1 G^T singular); then lambda <- max(0, lambda + rho g(z)). At an exact inner
// solution W (z - x) + G^T lambda = 0 holds with the updated lambda, and each outer step shrinks
// the violation by about 1 / (1 + rho sigma), sigma the smallest singular value of the active
// rows scaled by W^-1/2. rho starts soft (1e-4 of its working value, so that few rows change
// side per Newton step from the unconstrained start) and grows tenfold per outer step, and
// beyond its working value whenever a step gains less than a tenfold.

#include <weft/collision/ZoneQp.h>

#include <Eigen/SparseCore>

namespace weft::collision {

struct SparseZoneQp {
  Eigen::VectorXd x;                               // n
  Eigen::VectorXd weights;                         // n, > 0
  Eigen::SparseMatrix<double, Eigen::RowMajor> G;  // m x n
  Eigen::VectorXd h;                               // m
};

// iterations counts the inner Newton steps; options.maxIterations <= 0 means 500 of them.
ZoneQpSolution solveSparseZoneQp(const SparseZoneQp& qp, const ZoneQpOptions& options = {});

// The same QP with a dense G (for the gradient routes of ZoneQp.h and for tests).
ZoneQp toDense(const SparseZoneQp& qp);

}  // namespace weft::collision
