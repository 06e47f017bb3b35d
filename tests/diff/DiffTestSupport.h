#pragma once
// Scenes for the gradient tests: a small cloth hanging in wind (6 x 6 quads, a few tens of
// steps) with every kind of differentiable parameter present, and targets for its task loss
// simulated from the same scene with other parameter values.

#include <support/TempDir.h>
#include <weft/diff/Backpropagation.h>
#include <weft/diff/GradientCheck.h>
#include <weft/scene/Scene.h>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace weft::test {

// The hanging cloth in a sinusoidal wind, with a constant nodal force on a bottom vertex and an
// initial velocity; no task yet. 0.4 m, `quads` x `quads`, dt 0.01.
nlohmann::json windClothScene(int quads = 6, int steps = 25);

// Simulates `document` (tightly converged) and writes its positions ([states, vertices, 3]) as
// .npy to `path`. Returns the path.
std::string writeTargetTrajectory(const nlohmann::json& document, const std::string& path);

// Adds task {loss: {<kind>: {target}}, parameters} to the document.
void addTask(nlohmann::json& document, const std::string& kind, const std::string& target,
             const std::vector<std::string>& parameters);

// The hanging wind cloth above (6 x 6 quads, 0.4 m, wind, a nodal force) with corner 0
// fixed and the other top corner (vertex 6) on a handle: a Hermite spline through three knots at
// 0, 0.1 and 0.2 s (the run lasts 0.25 s, so the last steps hold the end point), attachment
// stiffness 500 N/m so that the handle's spring is soft enough to matter.
nlohmann::json handleScene(int steps = 25);

// The same cloth made soft and heavy (stretch 30 N/m, density 1 kg/m^2): h^2 k is below the nodal
// mass, so rho(P^{-1} Delta P) < 1 and DiffCloth's fixed-point iteration converges. On the stiff
// scene above it does not (compressed triangles make rho > 1; see AdjointSolverTest).
nlohmann::json softWindClothScene(int quads = 6, int steps = 25);

// `document` with a trajectory task whose target (the same scene with 5/6 of its stretch
// stiffness and wind strength 2.0) is written into `dir`.
Scene withTrajectoryTask(const TempDir& dir, const nlohmann::json& document,
                         const std::vector<std::string>& parameters);

// The DiffCloth authors' soft napkin without bending (assets/scenes/wind_reference.json, 200
// steps) at quads x quads, with a trajectory task on wind.strength against the same scene in a
// wind 1.5 times as strong, and the forward solver tightened to 1e-8: a backward pass whose
// adjoint grows by about 1e5 at 12^2 and 1e8 at 24^2 (AdjointGrowthTest).
Scene softNapkinTaskScene(const TempDir& dir, int quads);

// The wind scene with that task: what most adjoint tests differentiate.
Scene windTaskScene(const TempDir& dir, const std::vector<std::string>& parameters, int steps = 25);

// A 0.3 m x 0.1 m ribbon (6 x 2 quads) 1 mm above a 20 degree plane with friction 0.2 < tan 20
// deg: it slides, every node in the slip branch. 30 steps of 0.01 s, no task.
nlohmann::json inclineScene();

// The adjoint (direct backward solve, the solver-independent reference) against central finite
// differences for the task's parameters: every component nonzero and within 1e-4 relative, the
// loss positive, every forward step converged.
void expectAdjointMatchesFiniteDifferences(const Scene& scene);

// Gradients of one forward pass of `scene` (its task): by the direct solve, and by the `gmres`
// settings from the combination of the last 8 solutions and from the last solution alone.
struct HistoryGradients {
  GradientResult direct, combined, lastOnly;
};
HistoryGradients gradientsWithAndWithoutHistory(const Scene& scene, BackwardSettings gmres);

// A checked gradient: every component within `relative` of its finite difference plus `floor`
// times the largest component (components negligible against it carry the forward tolerance's
// noise in their finite differences); every forward run converged; the largest is nonzero.
void expectGradientAgreement(const GradientCheckReport& report, double relative = 1e-4,
                             double floor = 1e-6);

}  // namespace weft::test
