#pragma once
#include <vector>

namespace weft {

// What one time step did: the row of stats.csv.
struct StepStats {
  int step = 0;        // index of the state this step produced (1 = after the first step)
  double time = 0.0;   // s, at the end of the step
  int pdIterations = 0;
  double residual = 0.0;  // m/s^2, see SolverSettings::pdTolerance
  bool converged = false;
  int takeoff = 0, stick = 0, slip = 0;  // contact nodes per Signorini-Coulomb branch
  std::vector<double> moduleSeconds;     // aligned with Simulator::moduleNames()
};

}  // namespace weft
