#pragma once
// `weft bench impact_zones` (ImpactZonesBench.cpp): Liang et al. 2019 Table 1. A cloth crumpled
// in an upside-down square pyramid (assets/scenes/crumple.json with impact-zone self-collision)
// at several resolutions; every impact-zone QP of the run is differentiated twice with the same
// random dL/dz, by the full (n + m) KKT system of Liang Eq. 13 and by the QR route of Sec.
// 3.4.1-3.4.2, and the matrix sizes and times per QP backward are compared.

#include <string>
#include <vector>

namespace weft::bench {

struct ImpactZonesBenchOptions {
  bool quick = false;
  int threads = 1;               // OpenMP threads (the forward run; the zone backward is serial)
  std::vector<int> resolutions;  // quads per side; empty: 16, 32, 64 (quick: 8, 16)
  int steps = 0;                 // simulated steps per resolution; <= 0: the benchmark's own
};

// One zone QP's backward pass by both routes (ImpactZonesBench.cpp's timeZoneBackward).
struct ZoneBackwardSample {
  int n = 0;       // variables: 3 x the zone's free nodes
  int m = 0;       // constraint rows (impacts)
  int active = 0;  // rows with lambda > 0: what the QR route factors
  int rank = 0;    // numerical rank of those rows: the QR route's matrix size
  double kktSeconds = 0.0, qrSeconds = 0.0;  // per call, averaged over repeated calls
  bool kktOk = false;                        // false: Eq. 13's matrix was singular
  // Rows tight at the solution (|G_j z + h_j| <= 1e-9 (|h_j| + sum_k |G_jk z_k|)) with
  // lambda_j = 0: the degenerate case, where Eq. 13's row j is zero and its matrix singular.
  int tightWithoutMultiplier = 0;
  // Where kktOk: max |QR - KKT| / max |KKT| over dL/dx, and over dL/dx, dL/dG, dL/dh together.
  double differenceDx = 0.0, differenceAll = 0.0;
};

struct MeanSd {
  double mean = 0.0, sd = 0.0;  // sample standard deviation (0 for fewer than two values)
};
MeanSd meanSd(const std::vector<double>& values);

// One resolution's row of the table, from its zones' samples.
struct ImpactZonesSummary {
  int zones = 0;
  int kktSingular = 0;
  int rankDeficient = 0;   // zones whose active rows were dependent (rank < active)
  int withoutActive = 0;   // zones with no row at lambda > 0 (nothing to factor)
  int degenerate = 0;      // zones with a row tight at lambda = 0 (tightWithoutMultiplier > 0)
  MeanSd kktSize, qrSize;  // n + m; rank
  MeanSd kktSeconds, qrSeconds;
  double sizeRatio = 0.0;      // mean KKT size / mean QR size
  double speedup = 0.0;        // mean KKT seconds / mean QR seconds
  double medianSpeedup = 0.0;  // median over zones of KKT seconds / QR seconds
  double maxDifferenceDx = 0.0, maxDifferenceAll = 0.0;  // over the zones where kktOk
};
ImpactZonesSummary summariseZones(const std::vector<ZoneBackwardSample>& samples);

// Writes the tables into `outDir` (staged); returns the exit code.
int runImpactZonesBench(const ImpactZonesBenchOptions& options, const std::string& outDir);

}  // namespace weft::bench
