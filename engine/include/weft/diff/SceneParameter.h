#pragma once
// One differentiable scene parameter, addressed by its JSON path in the scene document (the same
// paths `--set` and `task.parameters` use), e.g. "cloths.0.material.stretch" or
// "wind.direction.2". Resolving a path checks that the adjoint knows how the parameter enters
// the step equations (ParameterPartials), so an unsupported path is an input error before any
// simulation runs.

#include <weft/scene/Scene.h>

#include <limits>
#include <string>
#include <vector>

namespace weft {

struct SceneParameter {
  enum class Kind {
    Stretch,                // cloths.K.material.stretch: scales the cloth's stretch weights
    Bend,                   // cloths.K.material.bend: scales the cloth's bending weights
    Density,                // cloths.K.material.density: scales mass, inertia and gravity
    InitialVelocity,        // cloths.K.initial_velocity.i: enters v_0
    NodalForce,             // cloths.K.forces.J.force.i: constant f_ext on the listed vertices
    WindStrength,           // wind.strength
    WindDirection,          // wind.direction.i
    WindFrequency,          // wind.frequency
    WindPhase,              // wind.phase
    Gravity,                // gravity.i
    ObstacleFriction,       // obstacles.J.friction (index = J): the slip branch's dr/dmu
    SelfCollisionFriction,  // cloths.K.self_collision.friction: pairs take the mean of both cloths'
    // Handles (moving attachments) and attachments, J = index in cloths.K.attachments:
    HandleOffset,         // ...attachments.J.trajectory.keyframes.P.offset.i or
                          // ...attachments.J.trajectory.hermite.points.P.i (knot P's offset)
    HandleTangent,        // ...attachments.J.trajectory.hermite.tangents.P.i (knot P's tangent)
    AttachmentStiffness,  // ...attachments.J.stiffness (fixed or handle; must be in the file)
  };
  std::string path;
  Kind kind = Kind::Stretch;
  int cloth = -1;      // cloth index, for per-cloth parameters
  int index = -1;      // force (NodalForce) or attachment (Handle*, AttachmentStiffness) index
  int component = -1;  // vector component 0..2 (InitialVelocity, NodalForce, WindDirection,
                       // Gravity, HandleOffset, HandleTangent)
  int knot = -1;       // trajectory knot (HandleOffset, HandleTangent)

  // Where the bounds and the optional log scale of an optimisation will live (set by `weft
  // optimize` from the task; unused by the gradient itself). With logScale the optimiser works
  // on log(value) and the chain rule multiplies the gradient by the value.
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  bool logScale = false;
};

// Resolves `path` against the validated scene. Throws InputError(scene.file, where, ...) when
// the path names no number in the scene or a value the adjoint cannot differentiate yet.
// `where` is what the message names: the option ("--param <path>") or the JSON path of the
// task entry ("task.parameters.1").
SceneParameter resolveSceneParameter(const Scene& scene, const std::string& path,
                                     const std::string& where);

// The parameter's current value, read from the typed scene.
double parameterValue(const Scene& scene, const SceneParameter& parameter);

// Writes `value` into the typed scene (and its document, which stays the scene's description),
// checked as the loader checks the file (scene/ValueChecks.h): an out-of-range value throws the
// InputError the same scene file would give. Reads no file and rebuilds nothing, so an objective
// evaluation can set its parameters on a copy of the loaded scene.
void setParameterValue(Scene& scene, const SceneParameter& parameter, double value);

// Every path of the scene document that resolveSceneParameter accepts, in the document's key
// order: the parameters a user may choose to optimise (the editor's Optimise tab offers them).
// Lists of more than three numbers (vertex lists), meshes and the task itself hold no parameter
// and are not visited.
std::vector<std::string> differentiableParameterPaths(const Scene& scene);

}  // namespace weft
