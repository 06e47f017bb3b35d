#include <weft/physics/SystemMatrix.h>

#include <weft/core/Error.h>

namespace weft {

SystemMatrix::SystemMatrix(const Eigen::VectorXd& mass,
                           const std::vector<std::unique_ptr<ProjectiveConstraint>>& constraints,
                           double h) {
  system_ = assembleSystemMatrix(mass, constraints, h);
  rows_ = system_;
  if (!cholesky_.factorize(system_))
    throw NumericalError(0, "solver", "system matrix P is not positive definite");
}

void SystemMatrix::multiply(const NodeMatrix& in, NodeMatrix& out) const {
  const int m = static_cast<int>(rows_.rows());
  const int* outer = rows_.outerIndexPtr();
  const int* inner = rows_.innerIndexPtr();
  const double* value = rows_.valuePtr();
  const double *ix = in.col(0).data(), *iy = in.col(1).data(), *iz = in.col(2).data();
  double *ox = out.col(0).data(), *oy = out.col(1).data(), *oz = out.col(2).data();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < m; ++i) {
    double sx = 0.0, sy = 0.0, sz = 0.0;
    for (int k = outer[i]; k < outer[i + 1]; ++k) {
      const int j = inner[k];
      sx += value[k] * ix[j], sy += value[k] * iy[j], sz += value[k] * iz[j];
    }
    ox[i] = sx, oy[i] = sy, oz[i] = sz;
  }
}

}  // namespace weft
