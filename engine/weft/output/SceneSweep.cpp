#include <weft/output/SceneSweep.h>

#include <weft/core/Error.h>
#include <weft/io/AtomicFile.h>
#include <weft/output/RunWriter.h>
#include <weft/physics/Simulator.h>
#include <weft/record/ConvergenceReport.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <sstream>

namespace weft {
namespace {

// Summary fields that say how long or how big a run was on its machine, not what it computed:
// the last columns of the file, the only ones that differ between a serial and an MPI sweep.
const std::vector<std::string> kTimingColumns = {"seconds", "seconds_per_step", "peak_memory_mb"};
// Fields that name the run rather than describe it, or are timings per module (a nested table).
const std::vector<std::string> kLeftOut = {"scene", "scene_file", "scene_directory", "modules",
                                           "threads"};

bool contains(const std::vector<std::string>& list, const std::string& s) {
  return std::find(list.begin(), list.end(), s) != list.end();
}

// summary.json's scalar figures as "a.b" -> value text (JSON's shortest round-trip form).
void flatten(const nlohmann::json& j, const std::string& prefix,
             std::vector<std::pair<std::string, std::string>>& out) {
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string key = prefix.empty() ? it.key() : prefix + "." + it.key();
    if (prefix.empty() && contains(kLeftOut, key)) continue;
    if (it->is_object())
      flatten(*it, key, out);
    else if (it->is_string())
      out.emplace_back(key, it->get<std::string>());
    else if (!it->is_array())
      out.emplace_back(key, it->dump());
  }
}

std::string csvCell(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string describe(const std::vector<SceneOverride>& combination, std::size_t from) {
  std::string text;
  for (std::size_t i = from; i < combination.size(); ++i)
    text += (text.empty() ? "" : ", ") + combination[i].path + "=" + combination[i].value;
  return text;
}

}  // namespace

SweepAxis parseSweepAxis(const std::string& text, const std::string& file) {
  const std::string where = "--set-grid " + text;
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError(file, where, "expected PATH=VALUE,VALUE,...");
  SweepAxis axis{text.substr(0, eq), {}};
  std::string value;
  int depth = 0;
  bool quoted = false;
  for (std::size_t i = eq + 1; i <= text.size(); ++i) {
    const char c = i < text.size() ? text[i] : ',';
    if (quoted) {
      if (c == '"') quoted = false;
    } else if (c == '"') {
      quoted = true;
    } else if (c == '[' || c == '{') {
      ++depth;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    } else if (c == ',' && depth == 0) {
      if (value.empty()) throw InputError(file, where, "empty value in the list");
      axis.values.push_back(value);
      value.clear();
      continue;
    }
    if (i < text.size()) value += c;
  }
  if (quoted || depth != 0) throw InputError(file, where, "unbalanced quotes or brackets");
  return axis;
}

std::vector<std::vector<SceneOverride>> sweepCombinations(const SweepSettings& settings) {
  std::vector<std::vector<SceneOverride>> combinations{settings.overrides};
  for (const SweepAxis& axis : settings.axes) {
    std::vector<std::vector<SceneOverride>> next;
    for (const std::vector<SceneOverride>& c : combinations)
      for (const std::string& v : axis.values) {
        next.push_back(c);
        next.back().push_back({axis.path, v});
      }
    combinations = std::move(next);
  }
  return combinations;
}

void checkSweepCombinations(const SweepSettings& settings) {
  const std::vector<std::vector<SceneOverride>> combinations = sweepCombinations(settings);
  const std::size_t fixed = settings.overrides.size();
  for (std::size_t k = 0; k < combinations.size(); ++k) {
    try {
      loadScene(settings.sceneFile, combinations[k]);
    } catch (const InputError& e) {
      throw InputError(e.file(), e.path(),
                       e.reason() + " (combination " + std::to_string(k) + ": " +
                           describe(combinations[k], fixed) + ")");
    }
  }
}

SweepOutcome runSweep(const SweepSettings& settings, WorkDistributor& workers,
                      const std::string& csvPath) {
  const std::vector<std::vector<SceneOverride>> combinations = sweepCombinations(settings);
  const std::size_t fixed = settings.overrides.size();

  // One run: its summary, flattened, as JSON [[key, value], ...] (the item's bytes).
  const auto run = [&](std::size_t k) {
    const Scene scene = loadScene(settings.sceneFile, combinations[k]);
    const int steps = settings.steps >= 0 ? settings.steps : scene.time.steps;
    const auto start = std::chrono::steady_clock::now();
    Simulator sim(scene);
    std::vector<StepStats> stats;
    stats.reserve(static_cast<std::size_t>(steps));
    for (int s = 0; s < steps; ++s) stats.push_back(sim.step());
    RunSummary summary;
    summary.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    summary.moduleNames = sim.moduleNames();
    summary.moduleSeconds = sim.moduleSeconds();
    std::vector<std::pair<std::string, std::string>> figures;
    flatten(summarize(scene, sim.cloth().nodeCount(), stats, summary), "", figures);
    return nlohmann::json(figures).dump();
  };
  const std::vector<WorkItemResult> results = workers.map(combinations.size(), run);

  SweepOutcome outcome;
  outcome.combinations = combinations.size();
  std::vector<std::vector<std::pair<std::string, std::string>>> rows(results.size());
  std::vector<std::string> columns;  // figures in the first successful row's order
  for (std::size_t k = 0; k < results.size(); ++k) {
    const WorkItemResult& r = results[k];
    if (!r.ok) {
      ++outcome.failed;
      outcome.worstExitCode = std::max(outcome.worstExitCode, r.exitCode);
      outcome.failures.push_back("combination " + std::to_string(k) + " (" +
                                 describe(combinations[k], fixed) + ") on rank " +
                                 std::to_string(r.rank) + ": " + r.message);
      continue;
    }
    rows[k] = nlohmann::json::parse(r.data).get<std::vector<std::pair<std::string, std::string>>>();
    for (const auto& [key, value] : rows[k]) {
      if (key == "pd.unconverged_steps" && value != "0") ++outcome.unconvergedRuns;
      if (!contains(columns, key) && !contains(kTimingColumns, key)) columns.push_back(key);
    }
  }
  if (!workers.isRoot()) return outcome;

  std::ostringstream csv;
  csv << "combination";
  for (const SweepAxis& axis : settings.axes) csv << "," << csvCell(axis.path);
  csv << ",status";
  for (const std::string& c : columns) csv << "," << c;
  for (const std::string& c : kTimingColumns) csv << "," << c;
  csv << "\n";
  for (std::size_t k = 0; k < results.size(); ++k) {
    csv << k;
    for (std::size_t a = fixed; a < combinations[k].size(); ++a)
      csv << "," << csvCell(combinations[k][a].value);
    csv << ","
        << csvCell(results[k].ok
                       ? "ok"
                       : "exit " + std::to_string(results[k].exitCode) + ": " + results[k].message);
    const auto cell = [&](const std::string& key) {
      for (const auto& [k2, v] : rows[k])
        if (k2 == key) return csvCell(v);
      return std::string();
    };
    for (const std::string& c : columns) csv << "," << cell(c);
    for (const std::string& c : kTimingColumns) csv << "," << cell(c);
    csv << "\n";
  }
  writeFileAtomically(csvPath, csv.str());
  return outcome;
}

}  // namespace weft
