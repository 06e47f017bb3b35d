#pragma once
// Shared checks of the paper's task scenes (Sphere, Hat, Sock; DiffCloth Sec. 6): loading an
// asset scene with `--set`-style overrides, the contact set of a tightly converged run, and the
// adjoint-vs-finite-difference agreement (expectGradientAgreement, DiffTestSupport.h).
//
// Why the contact set: the loss is a smooth function of the parameters only while every contact
// stays in its Signorini-Coulomb branch (DiffCloth Sec. 5.1): a node that lands, takes off, or
// switches between stick and slip between the two finite-difference runs makes a jump or a kink
// that no derivative describes. The gradient checks therefore run at reduced sizes where the
// contact set is the same at theta - d, theta and theta + d, and assert that it is.

#include <diff/DiffTestSupport.h>
#include <weft/diff/ForwardPass.h>
#include <weft/diff/GradientCheck.h>
#include <weft/diff/ParameterSet.h>
#include <weft/optim/LbfgsbOptimizer.h>
#include <weft/optim/SimulationObjective.h>
#include <weft/scene/SceneLoader.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace weft::test {

inline std::string assetScene(const std::string& name) {
  return std::string(WEFT_ASSET_DIR) + "/scenes/" + name + ".json";
}

// The asset scene `name` with `overrides` applied exactly as `weft ... --set PATH=VALUE` does.
inline Scene loadAssetScene(
    const std::string& name,
    const std::vector<std::pair<std::string, std::string>>& overrides = {}) {
  std::vector<SceneOverride> list;
  for (const auto& [path, value] : overrides) list.push_back({path, value});
  return loadScene(assetScene(name), list);
}

// Every contact of every step of the run (as GradientCheck runs it: Newton-PCG to 1e-8 m/s^2):
// (step, node, obstacle or -1, partner or -1, branch).
using ContactKey = std::tuple<int, int, int, int, int>;
inline std::vector<ContactKey> contactSet(const Scene& scene, int* active = nullptr) {
  const ForwardPass pass = runForwardPass(withTightForwardSolver(scene, 1e-8));
  std::vector<ContactKey> keys;
  int stickOrSlip = 0;
  for (std::size_t n = 0; n < pass.trajectory.contacts.size(); ++n)
    for (const ContactPoint& p : pass.trajectory.contacts[n].points) {
      keys.emplace_back(static_cast<int>(n), p.node, p.obstacle, p.partner,
                        static_cast<int>(p.branch));
      if (p.branch == ContactBranch::Stick || p.branch == ContactBranch::Slip) ++stickOrSlip;
    }
  std::sort(keys.begin(), keys.end());
  if (active) *active = stickOrSlip;
  return keys;
}

// The contact set is the same at theta +- d for each of `paths` (d as GradientCheck takes it:
// eps |theta|, or eps when theta = 0), i.e. the finite differences see no contact event.
inline void expectContactSetUnchanged(const Scene& scene, const std::vector<std::string>& paths,
                                      double eps) {
  const std::vector<ContactKey> base = contactSet(scene);
  const ParameterSet parameters = ParameterSet::fromPaths(scene, paths);
  const Eigen::VectorXd values = parameters.values(scene);
  for (int i = 0; i < parameters.size(); ++i) {
    const double d = values[i] != 0.0 ? eps * std::abs(values[i]) : eps;
    for (double sign : {-1.0, 1.0}) {
      Eigen::VectorXd moved = values;
      moved[i] += sign * d;
      EXPECT_TRUE(contactSet(parameters.withValues(scene, moved)) == base)
          << paths[i] << (sign > 0 ? " + d" : " - d") << ": the contact set changes";
    }
  }
}

// A system-identification task is well posed for its test: every parameter has a finite box
// that holds the hidden value, and the scene's start is more than 15 % away from it.
inline void expectHiddenValuesInsideBoxesAndAwayFromStart(
    const Scene& scene, const ParameterSet& parameters,
    const std::map<std::string, double>& hiddenByPath) {
  const SimulationObjective objective(scene, parameters);
  const Eigen::VectorXd start = parameters.values(scene);
  for (int i = 0; i < parameters.size(); ++i) {
    const SceneParameter& p = objective.space().parameters()[i];
    SCOPED_TRACE(p.path);
    const double hidden = hiddenByPath.at(p.path);
    EXPECT_TRUE(std::isfinite(p.lower) && std::isfinite(p.upper));
    EXPECT_GT(hidden, p.lower);
    EXPECT_LT(hidden, p.upper);
    EXPECT_GT(std::abs(start[i] - hidden), 0.15 * std::abs(hidden));
  }
}

// L-BFGS-B from the scene's start, at most `maxEvaluations` evaluations, recovers the hidden
// values: the loss falls below `lossFraction` of its initial value and every parameter ends
// within 2 % of its hidden value (or the fraction `tolerances` gives for its path).
inline void expectLbfgsbRecoversHiddenValues(const Scene& scene,
                                             const std::map<std::string, double>& hiddenByPath,
                                             int maxEvaluations, double lossFraction,
                                             const std::map<std::string, double>& tolerances = {}) {
  SimulationObjective objective(scene, ParameterSet::fromTask(scene));
  OptimizerSettings settings;
  settings.maxEvaluations = maxEvaluations;
  LbfgsbOptimizer optimizer(settings);
  const ParameterSpace& space = objective.space();
  const OptimizationResult r =
      optimizer.minimize(objective, space.toCoordinates(space.initialValues()),
                         space.lowerCoordinates(), space.upperCoordinates());
  const double initial = optimizer.log().entries().front().loss;
  EXPECT_LT(r.loss, lossFraction * initial)
      << r.stopReason << ", " << r.evaluations << " evaluations";
  const Eigen::VectorXd values = space.toValues(r.x);
  for (int i = 0; i < values.size(); ++i) {
    const std::string& path = space.parameters()[i].path;
    const double tolerance = tolerances.count(path) ? tolerances.at(path) : 0.02;
    EXPECT_NEAR(values[i], hiddenByPath.at(path), tolerance * std::abs(hiddenByPath.at(path)))
        << path << " (" << r.evaluations << " evaluations, " << r.stopReason << ")";
  }
}

}  // namespace weft::test
