#pragma once
// The parameter values one evaluation of a stored comparison run simulated, read back from the
// run's parameters/<task>_<method>_<seed>.csv (evaluation, then one column per task parameter in
// scene units, as ApplicationsBench writes it), so that a table can look at a run's answer
// (where its handles went) without running anything again.

#include <weft/diff/ParameterSet.h>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace weft::bench {

// One line of a run store's CSV files (no quoting: names and numbers only), split at commas.
std::vector<std::string> splitCsvLine(const std::string& line);

// The values of `evaluation` in `file`, in the order of `parameters`. Throws InputError naming
// the file when it is missing, its header is not "evaluation" and the parameters' paths, a value
// is not a number, or the evaluation is not there.
Eigen::VectorXd storedParameterValues(const std::string& file, const ParameterSet& parameters,
                                      int evaluation);

}  // namespace weft::bench
