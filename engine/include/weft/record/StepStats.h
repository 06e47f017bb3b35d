#pragma once
#include <vector>

namespace weft {

// What one time step did: the row of stats.csv.
struct StepStats {
  int step = 0;       // index of the state this step produced (1 = after the first step)
  double time = 0.0;  // s, at the end of the step
  int pdIterations = 0;
  double residual = 0.0;  // m/s^2, see SolverSettings::pdTolerance
  bool converged = false;
  // Contacts (node-obstacle contacts and self-collision pairs) per Signorini-Coulomb branch, as
  // the step's last contact solve left them.
  int takeoff = 0, stick = 0, slip = 0;
  // Contact solve (contact scenes only): Gauss-Seidel sweeps summed over the step's PD
  // iterations, and the largest impulse change of the last sweep as a velocity (m/s).
  int contactSweeps = 0;
  double contactSweepChange = 0.0;
  // Contacts added after the solve because the path it took met them and the predicted path
  // did not (FrictionalContact::addMissedContacts); the step was then solved again.
  int lateContacts = 0;
  // The deepest node inside any obstacle's contact skin at the end of the step (m; 0 when none
  // is inside, and without obstacles): skin minus the node's signed distance to the surface.
  double depth = 0.0;
  // Adaptive time stepping (SolverSettings::maxHalvings): how many pieces the step was solved in
  // (1: whole) and the finest one's halvings (its dt is the scene's / 2^halvings). pdIterations,
  // contactSweeps and lateContacts then sum over every attempt, the rejected ones included;
  // residual, converged and depth are the worst accepted piece's.
  int substeps = 1;
  int halvings = 0;
  // Impact zones (self_collision.model "impact_zones", Liang 2019 Sec. 3.4), summed over the
  // step's pieces: detection rounds, zones solved, impact constraints in them, QP iterations;
  // impactsResolved is false when the round limit left impacts unresolved (then the step is not
  // collision-free), impactRigidZones the zones the failsafe translated rigidly (their QP failed,
  // or asked for a larger move than undoing the step), and impactMove the largest displacement
  // the response made (m).
  int impactRounds = 0, impactZones = 0, impactConstraints = 0, impactQpIterations = 0;
  int impactRigidZones = 0;
  bool impactsResolved = true;
  double impactMove = 0.0;
  std::vector<double> moduleSeconds;  // aligned with Simulator::moduleNames()
};

}  // namespace weft
