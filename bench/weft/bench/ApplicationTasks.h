#pragma once
// The tasks of `weft bench applications` (ApplicationsBench.h) and the methods it compares: the
// task table, one line per task, the budgets citing DiffCloth's Tables 2-3 where the paper has
// the task.

namespace weft::bench {

// The tasks, one line each: the name --tasks takes, the scene below assets/, and the budget of
// simulated steps per run (the same for every method), normally and under --quick.
struct ApplicationTask {
  const char* name;
  const char* scene;
  long long budget;
  long long quickBudget;
};
inline constexpr ApplicationTask kApplicationTasks[] = {
    {"napkin_4x4", "scenes/napkin_4x4.json", 20000, 2500},
    {"napkin_5x5", "scenes/napkin_5x5.json", 20000, 2500},
    {"napkin_7x7", "scenes/napkin_7x7.json", 20000, 2500},
    {"napkin_10x10", "scenes/napkin_10x10.json", 20000, 2500},
    {"wind_sysid", "scenes/wind_sysid.json", 3000, 600},
    // Sec. 6.4 and 6.3 (Table 3: L-BFGS-B converged in 6800 and 2750 steps, the ES in up to
    // 24800 and 10000); quick: 6 and 6 gradient evaluations.
    {"flag", "scenes/flag.json", 7200, 1200},
    {"dress", "scenes/dress.json", 6000, 1500},
    // Sec. 6.1, the T-shirt (Table 3: L-BFGS-B converged in 4500 steps, the ES in about 50000): 10
    // gradient evaluations of its 250 steps, about 0.25 s of one core a step; quick: 2.
    {"tshirt", "scenes/tshirt.json", 5000, 1000},
    // Sec. 6.1-6.2 (Table 3: L-BFGS-B converged in 2450, 11200 and 17600 steps). The Sock's forward
    // contact solve does not converge once the sock reaches the foot (docs/applications.md).
    {"sphere_sysid", "scenes/sphere_sysid.json", 7000, 1400},
    {"hat", "scenes/hat.json", 12000, 1600},
    {"sock", "scenes/sock.json", 17600, 1600},
};
// The one task --quick runs unless --tasks names others.
inline constexpr const char* kQuickApplicationTask = "napkin_4x4";

// The methods compared, in the tables' order (L-BFGS-B first: the others are measured against it).
struct ApplicationMethod {
  const char* name;   // makeOptimizer's
  const char* title;  // the paper's
};
inline constexpr ApplicationMethod kApplicationMethods[] = {
    {"lbfgsb", "L-BFGS-B"}, {"cmaes", "CMA-ES"}, {"es1p1", "(1+1)-ES"}};
inline constexpr int kApplicationMethodCount = 3;

}  // namespace weft::bench
