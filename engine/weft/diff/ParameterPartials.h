#pragma once
// The parameter side of one backward step: dL/dtheta += -z^T dG/dtheta, where
//
//   G(x_{n+1}; x_n, v_n, theta) = P x_{n+1} - M (x_n + h v_n) - h^2 f_ext(t_{n+1})
//                                 - h^2 sum_i w_i A_i^T p_i(x_{n+1})  =  0
//
// is the step's equation (the first-order condition of Eq. 3, written as Eq. 13 times M) and z
// solves K^T z = dL/dx_{n+1} (Eq. 19). Partials, all analytic:
//   stretch/bend k of cloth c: w = k * w_hat, so dG/dk = h^2 sum_{i in c} w_hat_i A_i^T (A_i x -
//   p_i(x))
//                              (the family's gradient, Eq. 17, at unit stiffness);
//   density rho of cloth c:    M = rho * area, gravity m g: dG/drho = area (x_{n+1} - x_n - h v_n -
//   h^2 g); wind (strength s, direction d, frequency f, phase phi), f_i = s area_i phi(t) d with
//                              phi = (sin(2 pi f t + phi0) + 1)/2: dG/dtheta = -h^2 df/dtheta;
//   constant nodal forces and gravity: dG/dF = -h^2 (selection);
//   handle targets: an attachment row (node j, stiffness k) adds h^2 k (x_j - x_hat_j(t)) to G
//                              (its P part and its projection p = x_hat, Sec. 3.1), so
//                              dG_j/d x_hat_j = -h^2 k I, chained through x_hat_j(t_{n+1}) =
//                              R(t) rest_j + offset(t), offset linear in the trajectory's knot
//                              values with the keyframe or Hermite weights
//                              (HandleTrajectory::controlWeight; DiffCloth Appendix B, Hat/Sock);
//   attachment stiffness k:    dG_j/dk = h^2 (x_j - x_hat_j) for each of its vertices j;
//   initial velocity: enters v_0 only, so it is read from dL/dv_0 at the end (Backpropagation).

#include <weft/diff/SceneParameter.h>
#include <weft/model/ClothModel.h>
#include <weft/physics/Model.h>
#include <weft/physics/ProjectiveConstraint.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <memory>
#include <vector>

namespace weft {

class ParameterPartials {
 public:
  // The model must outlive the partials.
  ParameterPartials(const Model& model, const std::vector<SceneParameter>& parameters);
  ~ParameterPartials();

  // gradient[k] += -z . dG/dtheta_k for the step from (x0, v0) to x1 ending at time t1.
  void accumulate(const NodeMatrix& x0, const NodeMatrix& v0, const NodeMatrix& x1, double t1,
                  const NodeMatrix& z, Eigen::VectorXd& gradient) const;
  // gradient[k] += dL/dtheta_k through the initial state (initial velocity parameters).
  void accumulateInitial(const NodeMatrix& dLdv0, Eigen::VectorXd& gradient) const;

 private:
  struct UnitFamily {  // a stiffness parameter's constraint family at unit stiffness
    std::unique_ptr<ProjectiveConstraint> constraint;
    Eigen::SparseMatrix<double> gram;  // sum_i w_hat_i A_i^T A_i
  };
  const Scene& scene_;
  const ClothModel& model_;
  std::vector<SceneParameter> parameters_;
  std::vector<UnitFamily> unit_;  // per parameter (empty for non-stiffness parameters)
  double h_;
  mutable NodeMatrix rows_, work_;
};

}  // namespace weft
