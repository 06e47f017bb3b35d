#pragma once
// One piece of a step that adaptive time stepping split (SolverSettings::maxHalvings): the solve
// of [t1 - h, t1] at h = dt / 2^halvings, with the model compiled at that h. The backward pass
// runs through a split step's pieces in reverse, each with its own P, Delta P and contacts.

#include <weft/core/Types.h>
#include <weft/record/StepContacts.h>

#include <memory>

namespace weft {

class Model;  // physics/Model.h

struct Substep {
  std::shared_ptr<const Model> model;  // the scene compiled at this piece's dt
  int halvings = 0;
  double time = 0.0;      // s, at the end of the piece
  NodeMatrix x0, v0;      // the state it starts from
  NodeMatrix x1;          // the state it ends in
  StepContacts contacts;  // contact scenes: its contacts as its solve left them
};

}  // namespace weft
