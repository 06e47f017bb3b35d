#pragma once
// solver.contact = "newton": semismooth Newton on the residual of the "pd" contact iteration's
// fixed point, G(x) = P x - b(x) - h r(f(x)) (PdContactSolve; DiffCloth Eqs. 8, 10-12): the same
// law and the same solution, reached in a few Newton steps where the PD iteration converges
// linearly. The law is solved with the mass sqrt(m_i P_ii) (which changes the iterates, not the
// solution), and the linear solves are preconditioned by P, or, once that is slow, by a
// factorisation of the clamped Hessian K+: P leaves one soft out-of-plane mode per node that PD
// and P-preconditioned Krylov methods converge slowly on. Steps without contacts take the same
// path unless solver.method is "newton" (then Newton-PCG); a stalled step is finished by the PD
// contact iteration (finishWithPerNodeIterations).

#include <weft/physics/Gmres.h>
#include <weft/physics/HessianAssembly.h>
#include <weft/physics/PdContactSolve.h>
#include <weft/physics/SparseCholesky.h>
#include <weft/physics/StepSolver.h>

#include <memory>

namespace weft {

class ContactNewtonSolve final : public StepSolver {
 public:
  explicit ContactNewtonSolve(const StepContext& ctx);
  // The detected contacts to the per-node solver, the law solved with the law mass m~.
  void prepareContacts(StepContext& ctx) override;
  void solve(StepContext& ctx) override;
  bool resolvesMissedContacts() const override { return true; }
  void record(const StepContext& ctx, StepContacts& out) const override;

 private:
  // The semismooth Newton iteration from ctx.iterate until ctx.solveLimit.
  void solveNewton(StepContext& ctx);
  // The PD contact iteration continues a stalled solve; the better result is the step's.
  void finishWithPerNodeIterations(StepContext& ctx);
  // The preconditioner: a CHOLMOD factor of the 3m x 3m clamped Hessian K+ = P - Delta P+ (the
  // `definite` projection derivatives), assembled from the constraints' element blocks
  // (HessianAssembly). False when the factorisation failed (the preconditioner then falls back
  // to P).
  bool factorizeStiffness(StepContext& ctx);
  // z = B r for the GMRES of solveNewton (r, z mass-scaled as there; one "solve").
  void applyPreconditioner(StepContext& ctx, const NodeMatrix& scaled, NodeMatrix& z);
  void traceResidualNodes(const StepContext& ctx,
                          const NodeMatrix& residual) const;  // WEFT_CONTACT_TRACE

  PdContactSolve pd_;  // finishWithPerNodeIterations
  // The law mass m~ (ContactSolver::setContacts): sqrt(m_i P_ii).
  Eigen::VectorXd lawMass_;
  NodeMatrix lawInput_, pinnedPart_, newtonResult_, coupling_;  // work buffers
  std::unique_ptr<HessianAssembly> stiffnessAssembly_;          // K+ (factorizeStiffness)
  Eigen::SparseMatrix<double> stiffness_;
  SparseCholesky stiffnessCholesky_{SparseCholesky::Use::Preconditioner};
  bool stiffnessFactored_ = false;
  // A factorisation of K+ costs so many iterations with P that a step starts from the previous
  // step's factor (solveNewton).
  bool keepStiffnessFactor_ = false;
  Gmres gmres_;
};

}  // namespace weft
