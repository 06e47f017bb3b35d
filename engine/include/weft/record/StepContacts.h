#pragma once
// All contacts of one time step and how their solve went: the per-step contact record the
// Trajectory keeps (steps 1..N), for the backward pass, the editor and the renderer.

#include <weft/record/ContactPoint.h>
#include <weft/record/StepStats.h>

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

// Adds the step's contacts per branch to stats (takeoff, stick, slip): both contact solves
// count from the record they leave.
inline void countBranches(const StepContacts& contacts, StepStats& stats) {
  for (const ContactPoint& p : contacts.points) {
    if (p.branch == ContactBranch::TakeOff)
      ++stats.takeoff;
    else if (p.branch == ContactBranch::Stick)
      ++stats.stick;
    else if (p.branch == ContactBranch::Slip)
      ++stats.slip;
  }
}

}  // namespace weft
