#pragma once
// The validated, in-memory scene: everything the engine needs, with defaults filled in and
// meshes built. Produced only by SceneLoader, which checks every key and value.

#include <weft/core/Types.h>
#include <weft/mesh/RigidTransform.h>
#include <weft/mesh/TriangleMesh.h>
#include <weft/scene/HandleTrajectory.h>

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace weft {

struct TimeSettings {
  double dt = 0.01;  // s
  int steps = 100;
};

struct BackwardSettings {
  // The adjoint's linear solve per step (engine/include/weft/diff/AdjointSolver.h): "gmres"
  // (Krylov, preconditioned by the factor of P), "fixed_point" (DiffCloth Eq. 20/30) or "direct"
  // (sparse LU).
  std::string method = "gmres";
  double tolerance = 1e-4;  // relative residual |g - K z| / |g| of each step's adjoint solve
  int maxIterations = 200;
  std::string fallback = "direct";  // "direct" (sparse LU) or "none"
  // GMRES's preconditioner: "p" (the prefactorised PD matrix P, as DiffCloth's Eq. 30 uses it),
  // "hessian" (a fresh Cholesky factor per step of P - Delta P with each projection's
  // derivative clamped to keep it definite: AdjointSystem::factorClampedHessian) or "auto"
  // (per step, P first and the Hessian where P is slow: GmresSolver).
  std::string preconditioner = "auto";
  // GMRES starts each step from the best combination of the last `history` steps' solutions
  // (diff/SolutionHistory.h); 0 starts from the last step's solution alone.
  int history = 8;
  // The parameter gradient's requested relative accuracy, |g - g_exact| / |g| (2-norms over the
  // parameters): an iterative backward pass is checked against a second one at a tolerance 100
  // times tighter, and tightened until the two agree to this (diff/GradientErrorControl.h).
  // 0 turns the check off: one pass, its error sized by a fit (diff/AdjointGrowth.h).
  double accuracy = 1e-3;
};

enum class Acceleration { None, Anderson };
// "newton": Newton with CG preconditioned by the prefactorised P (the default);
// "pd": local-global PD iterations (with Anderson acceleration unless turned off).
enum class SolverMethod { Newton, ProjectiveDynamics };
// Contact scenes (solver.contact): "newton" (default), semismooth Newton on the fixed point of
// the PD contact iteration (same law, same solution); "pd", DiffCloth's per-node
// Signorini-Coulomb solve inside PD iterations (ContactSolver.h), whatever `method` says;
// "active_set" (experimental), Newton-PCG with the contacts as an active set of constraints
// (ActiveContactSet.h).
enum class ContactMethod { ProjectiveDynamics, ActiveSet, Newton };

struct SolverSettings {
  SolverMethod method = SolverMethod::Newton;
  ContactMethod contact = ContactMethod::Newton;
  int pdIterations = 100;  // at most this many solves with P per step
  // Converged when the mass-weighted RMS imbalance of the implicit-Euler equations
  // (DiffCloth Eq. 3 gradient divided by nodal mass) falls below this, in m/s^2.
  double pdTolerance = 1e-4;
  Acceleration acceleration = Acceleration::Anderson;
  int andersonWindow = 5;
  // Adaptive time stepping: a step that does not converge is solved again as two halves, each
  // split further while it does not converge, down to dt / 2^maxHalvings (0: never split).
  int maxHalvings = 6;
  // A step-size controller on top: each step starts at the halvings the last one needed (one
  // finer after a failure, one coarser after two clean steps). Faster where hard steps come in
  // runs (an impact), but the discretisation then depends on the run's history, and a loss over
  // the run jumps further where a parameter change moves a split: off by default.
  bool rememberHalvings = false;
  BackwardSettings backward;
};

struct Material {
  double density = 0.1;  // kg/m^2 (areal)
  double stretch = 100;  // N/m (membrane)
  double bend = 0.0;     // N*m
  // How a hinge curved at rest is bent back (BendingConstraint.h): "magnitude" keeps the rest
  // curvature's magnitude along the current curvature (DiffCloth's); "oriented" carries the rest
  // curvature vector with the hinge's frame at the step's start, so it keeps its side.
  enum class BendModel { Magnitude, Oriented };
  BendModel bendModel = BendModel::Magnitude;
};

struct Attachment {
  enum class Kind { Fixed, Handle };
  Kind kind = Kind::Fixed;
  std::vector<int> vertices;    // cloth-local indices
  double stiffness = 1e4;       // N/m per vertex (PD attachment weight)
  HandleTrajectory trajectory;  // handles only
};

struct PointForce {
  std::vector<int> vertices;  // cloth-local indices
  Vec3 force = Vec3::Zero();  // N on each listed vertex
};

// A cloth's collisions with itself and with the other self-colliding cloths, by one or both of
// two models (scene key `self_collision.model`): DiffCloth's node-node contacts under the
// Signorini-Coulomb law ("node", the default), and Liang et al. 2019's continuous collision
// detection with non-rigid impact zones ("impact_zones"), which keeps every vertex-face and
// edge-edge pair at least `thickness` apart so that no edge passes through a face.
struct SelfCollision {
  bool nodeModel = true;
  bool impactZones = false;
  double radius = 0.004;     // m, node model: the contact distance between nodes
  double friction = 0.3;     // node model
  double thickness = 0.001;  // m, impact zones: the distance kept between surfaces (Liang Eq. 9)
};

struct Cloth {
  TriangleMesh mesh;  // rest mesh, transformed, in scene units (m)
  Material material;
  std::vector<Attachment> attachments;
  std::vector<PointForce> forces;
  Vec3 initialVelocity = Vec3::Zero();
  std::optional<SelfCollision> selfCollision;
};

struct Obstacle {
  enum class Shape { Plane, Sphere, Capsule, Box, Cylinder, Mesh };
  Shape shape = Shape::Plane;
  Vec3 point = Vec3::Zero();                // plane
  Vec3 normal = Vec3::UnitY();              // plane (unit)
  Vec3 center = Vec3::Zero();               // sphere, box
  double radius = 0.0;                      // sphere, capsule, cylinder
  Vec3 a = Vec3::Zero(), b = Vec3::Zero();  // capsule, cylinder axis end points
  Vec3 halfExtents = Vec3::Zero();          // box
  Mat3 rotation = Mat3::Identity();         // box orientation
  TriangleMesh mesh;                        // mesh obstacle (transformed)
  bool smoothNormals = true;                // mesh obstacle
  double friction = 0.0;
  // Contact skin (m): cloth nodes are kept this far outside the surface (extension of the spec,
  // key "thickness").
  double thickness = 1e-3;
  // Kinematic motion (extension, key "motion", same form as a handle's "trajectory"): the shape
  // above is the pose at offset zero; at time t a body point X is at motion->target(X, t), i.e.
  // rotated about the rotation centre and then translated. Absent: the obstacle is static.
  std::optional<HandleTrajectory> motion;
};

struct Wind {
  Vec3 direction = Vec3::UnitX();  // used as given: its length scales the pressure
  double strength = 0.0;           // N/m^2, spread over vertices by lumped area
  double frequency = 0.0;          // Hz
  double phase = 0.0;              // rad
  // DiffCloth's model: f = strength * area * 0.5 * (sin(2 pi frequency t + phase) + 1) * direction
  // ("sinusoid"), or without the time factor ("constant").
  bool constant = false;
  // The Flag's wind (DiffCloth Appendix B.4, Eq. 35: f_ext = 0.5 (sin(w t + phi) + 1) k d^T, k_i a
  // node's inverse distance to the flag centre at the first time step): with a falloff centre c,
  // node i's coefficient is k_i = 1 / |X_i - c| (1/m, X_i its initial position) in place of its
  // lumped area, and strength is in N m. `coefficients` holds k in scene order (the loader fills
  // it when falloffCenter is set; empty otherwise).
  std::optional<Vec3> falloffCenter;
  Eigen::VectorXd coefficients;
};

struct Task {
  nlohmann::json loss;                  // validated structure; interpreted by the diff concern
  std::vector<std::string> parameters;  // JSON paths of scalars in the scene
  // Optional explicit optimisation bounds (task.bounds: {"<parameter path>": [lower, upper]}, a
  // null side meaning unbounded); `weft optimize` uses them instead of the parameter kind's
  // default bounds.
  struct Bound {
    std::string path;
    double lower, upper;
  };
  std::vector<Bound> bounds;
};

struct Scene {
  std::string name;
  std::string file;       // the scene file as given
  std::string directory;  // for resolving relative paths
  TimeSettings time;
  std::optional<Vec3> gravity;
  SolverSettings solver;
  std::vector<Cloth> cloths;
  std::vector<Obstacle> obstacles;
  std::optional<Wind> wind;
  std::optional<Task> task;
  nlohmann::json document;            // the document as loaded, overrides applied
  std::vector<std::string> warnings;  // repaired or suspicious input, for the user

  int vertexCount() const;
  bool hasSelfCollision() const;  // node-model self-collision (part of the contact solve)
  bool hasImpactZones() const;    // some cloth's self_collision.model has "impact_zones"
};

}  // namespace weft
