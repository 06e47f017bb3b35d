#include "StepStatsTable.h"

#include "NumpyArrays.h"

namespace weft::python {

namespace py = pybind11;

namespace {

// The fields, named as in stats.csv where it has them; `bool` fields as NumPy bools.
template <typename Visit>
void forEachField(Visit&& visit) {
  visit("step", [](const StepStats& s) { return s.step; });
  visit("time", [](const StepStats& s) { return s.time; });
  visit("converged", [](const StepStats& s) { return s.converged; });
  visit("residual", [](const StepStats& s) { return s.residual; });
  visit("pd_iterations", [](const StepStats& s) { return s.pdIterations; });
  visit("takeoff", [](const StepStats& s) { return s.takeoff; });
  visit("stick", [](const StepStats& s) { return s.stick; });
  visit("slip", [](const StepStats& s) { return s.slip; });
  visit("contact_sweeps", [](const StepStats& s) { return s.contactSweeps; });
  visit("late_contacts", [](const StepStats& s) { return s.lateContacts; });
  visit("depth", [](const StepStats& s) { return s.depth; });
  visit("substeps", [](const StepStats& s) { return s.substeps; });
  visit("halvings", [](const StepStats& s) { return s.halvings; });
  visit("impact_rounds", [](const StepStats& s) { return s.impactRounds; });
  visit("impact_zones", [](const StepStats& s) { return s.impactZones; });
  visit("impact_constraints", [](const StepStats& s) { return s.impactConstraints; });
  visit("impact_qp_iterations", [](const StepStats& s) { return s.impactQpIterations; });
  visit("impacts_resolved", [](const StepStats& s) { return s.impactsResolved; });
  visit("impact_move", [](const StepStats& s) { return s.impactMove; });
  visit("impact_rigid_zones", [](const StepStats& s) { return s.impactRigidZones; });
}

}  // namespace

py::dict stepStatsDict(const StepStats& stats) {
  py::dict out;
  forEachField([&](const char* name, auto field) { out[name] = field(stats); });
  return out;
}

py::dict stepStatsTable(const std::vector<StepStats>& steps) {
  py::dict out;
  forEachField([&](const char* name, auto field) {
    using T = decltype(field(StepStats{}));
    std::vector<T> column;
    column.reserve(steps.size());
    for (const StepStats& s : steps) column.push_back(field(s));
    if constexpr (std::is_same_v<T, bool>) {
      // std::vector<bool> has no data(): NumPy bools from bytes.
      py::array_t<bool> a(static_cast<py::ssize_t>(column.size()));
      for (std::size_t i = 0; i < column.size(); ++i) a.mutable_data()[i] = column[i];
      out[name] = a;
    } else {
      out[name] = vectorArray(column);
    }
  });
  return out;
}

}  // namespace weft::python
