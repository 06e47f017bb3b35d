#pragma once
// A run's per-step statistics (StepStats, the columns of stats.csv) for Python: one step as a
// dict, or a run's steps as a dict of 1-D NumPy arrays, one per field.

#include <weft/record/StepStats.h>

#include <pybind11/pybind11.h>

#include <vector>

namespace weft::python {

pybind11::dict stepStatsDict(const StepStats& stats);
pybind11::dict stepStatsTable(const std::vector<StepStats>& steps);

}  // namespace weft::python
