#pragma once
// One (task, method, seed) run of `weft bench applications` and its file in the run store
// (DIR.partial/<task>_<method>_<seed>.csv): the columns of kRunColumns, one row per evaluation,
// written atomically when the run ends and read back, checked line by line, on --resume.

#include "ApplicationTasks.h"
#include "LossEnvelope.h"

#include <string>
#include <vector>

namespace weft::bench {

struct ApplicationRun {
  int method = 0;  // index into kApplicationMethods
  int seed = 0;
  LossCurve curve;
  double seconds = 0.0;
  std::string stop;
  std::vector<std::vector<std::string>> rows;  // its rows of applications.csv
  bool resumed = false;
  // Tasks with handles and obstacles: the deepest handle target inside an obstacle at the run's
  // best evaluation (m, 0 when none enters; HandleObstacleCheck.h).
  double handleDepth = 0.0;
};

// A run file's header, and the columns of applications.csv.
extern const std::vector<std::string> kRunColumns;

// The fields joined by commas, with a newline (no quoting: names and numbers only).
std::string joinCsvLine(const std::vector<std::string>& fields);

// The evaluation (1-based, as logged) with the run's lowest loss, the first of equals.
int bestEvaluation(const ApplicationRun& run);

// Writes the run's rows under the header, atomically.
void writeRunFile(const std::string& path, const ApplicationRun& run);

// Reads a stored run of `task`, `method` and `seed` back. Throws InputError naming the file and
// the line when it cannot be read, its header is not kRunColumns, a row has another field count,
// belongs to another run, or its steps, wall_s or loss are not numbers, or steps decrease.
ApplicationRun readRunFile(const std::string& path, const ApplicationTask& task, int method,
                           int seed);

}  // namespace weft::bench
