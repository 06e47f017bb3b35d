#pragma once
// The recorded forward run: the model it was simulated with, the converged state of every step
// (what the backward pass needs to rebuild each step's projections and contact branches) and the
// per-step statistics.

#include <weft/core/Types.h>
#include <weft/record/StepContacts.h>
#include <weft/record/StepStats.h>
#include <weft/record/Substep.h>

#include <memory>
#include <string>
#include <vector>

namespace weft {

class Model;  // physics/Model.h: the trajectory holds it, the backward pass reads it

struct Trajectory {
  // The compiled scene the states were simulated with (set by Simulator::run); null for a run
  // read back from a run folder, which cannot be differentiated.
  std::shared_ptr<const Model> model;
  std::vector<NodeMatrix> positions;   // states 0..N
  std::vector<NodeMatrix> velocities;  // states 0..N
  std::vector<StepStats> steps;        // steps 1..N
  // Steps 1..N: every contact with its branch, frame, impulse and velocity. Empty when the
  // scene has no obstacles and no self-collision.
  std::vector<StepContacts> contacts;
  // Steps 1..N: the pieces of a step adaptive time stepping split (Substep.h), in order; empty
  // for a step solved whole. The step's state and contacts above are its last piece's.
  std::vector<std::vector<Substep>> substeps;
  std::vector<std::string> moduleNames;

  int stepCount() const { return static_cast<int>(steps.size()); }
  int nodeCount() const {
    return positions.empty() ? 0 : static_cast<int>(positions.front().rows());
  }
  // positions as one [states, nodes, 3] C-order array (the layout of positions.npy).
  std::vector<double> flattenedPositions() const;
};

}  // namespace weft
