#pragma once
// All contacts of one time step and how their solve went: the per-step contact record the
// Trajectory keeps (steps 1..N), for the backward pass, the editor and the renderer.

#include <weft/contact/ContactPoint.h>

#include <vector>

namespace weft {

struct StepContacts {
  // Node-obstacle contacts first (by node, then obstacle), then self-collision pairs in the
  // solver's layer order.
  std::vector<ContactPoint> points;
  // Gauss-Seidel sweeps over the contacts in the whole step (summed over PD iterations; one per
  // iteration when no node has two contacts) and the largest impulse change of the last sweep,
  // as a velocity (m/s).
  int sweeps = 0;
  double sweepChange = 0.0;
  int pairLayers = 0;  // Gauss-Seidel layers of the self-collision pairs
};

}  // namespace weft
