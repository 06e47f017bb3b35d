#include "BenchTable.h"

#include "CommandLine.h"

#include <weft/core/Error.h>

#include <sys/utsname.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <thread>

namespace weft::cli {

void BenchTable::writeCsv(const std::string& path) const {
  std::ofstream out(path);
  for (std::size_t i = 0; i < columns_.size(); ++i) out << (i ? "," : "") << columns_[i];
  out << "\n";
  for (const auto& row : rows_) {
    for (std::size_t i = 0; i < row.size(); ++i) out << (i ? "," : "") << row[i];
    out << "\n";
  }
  if (!out) throw InputError(path, "output", "write failed");
}

void BenchTable::writeMarkdown(const std::string& path, const std::string& title,
                               const std::string& preamble) const {
  std::ofstream out(path);
  writeMarkdown(out, title, preamble);
  if (!out) throw InputError(path, "output", "write failed");
}

void BenchTable::writeMarkdown(std::ostream& out, const std::string& title,
                               const std::string& preamble) const {
  out << "## " << title << "\n\n" << preamble << "\n\n|";
  for (const auto& c : columns_) out << " " << c << " |";
  out << "\n|";
  for (std::size_t i = 0; i < columns_.size(); ++i) out << " ---: |";
  out << "\n";
  for (const auto& row : rows_) {
    out << "|";
    for (const auto& cell : row) out << " " << cell << " |";
    out << "\n";
  }
}

bool plotSeries(const std::string& png, const std::string& title, const std::string& xLabel,
                const std::string& yLabel, const std::vector<PlotSeries>& series, bool logX,
                bool logY, std::string& reason) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
    reason = "gnuplot is not installed (apt-get install gnuplot-nox); no plot written";
    return false;
  }
  const std::string script = png + ".gp";
  {
    std::ofstream gp(script);
    gp << "set terminal pngcairo size 900,600 noenhanced\n"
       << "set output '" << png << "'\n"
       << "set title '" << title << "'\n"
       << "set xlabel '" << xLabel << "'\nset ylabel '" << yLabel << "'\n"
       << "set grid\nset key outside right\n";
    if (logX) gp << "set logscale x\n";
    if (logY) gp << "set logscale y\nset format y '%.0e'\n";
    gp << "plot ";
    for (std::size_t s = 0; s < series.size(); ++s)
      gp << (s ? ", " : "") << "'-' using 1:2 with " << series[s].style << " title '"
         << series[s].title << "'";
    gp << "\n";
    for (const auto& s : series) {
      for (std::size_t i = 0; i < s.x.size(); ++i)
        if (!logY || s.y[i] > 0) gp << s.x[i] << " " << s.y[i] << "\n";
      gp << "e\n";
    }
  }
  const int rc = std::system(("gnuplot '" + script + "' 2>/dev/null").c_str());
  std::remove(script.c_str());
  if (rc != 0) {
    reason = "gnuplot failed";
    return false;
  }
  return true;
}

std::string formatNumber(double v, int precision) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", precision, v);
  return buf;
}

std::string machineDescription() {
  utsname u{};
  uname(&u);
  std::string cpu = "unknown CPU";
  std::ifstream info("/proc/cpuinfo");
  for (std::string line; std::getline(info, line);)
    if (line.rfind("model name", 0) == 0) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  std::ostringstream s;
  s << u.sysname << " " << u.machine << ", " << std::thread::hardware_concurrency() << " cores, "
    << cpu;
  return s.str();
}

std::vector<std::string> benchNames(const CommandLine& cl, const std::string& option,
                                    const std::string& fallback,
                                    const std::vector<std::string>& known) {
  const std::string text = cl.value(option, fallback);
  std::vector<std::string> out;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t comma = std::min(text.find(',', begin), text.size());
    out.push_back(text.substr(begin, comma - begin));
    if (std::find(known.begin(), known.end(), out.back()) == known.end()) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      cl.fail(option, "unknown name '" + out.back() + "' (known: " + list + ")");
    }
    begin = comma + 1;
  }
  return out;
}

std::vector<int> benchResolutions(const CommandLine& cl, std::vector<int> fallback) {
  if (!cl.has("--resolutions")) return fallback;
  std::vector<int> out;
  const std::string text = cl.value("--resolutions", "");
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t comma = std::min(text.find(',', begin), text.size());
    const std::string item = text.substr(begin, comma - begin);
    char* end = nullptr;
    const long n = std::strtol(item.c_str(), &end, 10);
    if (item.empty() || *end != '\0' || n < 1 || n > 1024)
      cl.fail(
          "--resolutions",
          "expects quads per side as a comma-separated list, e.g. 12,24,48; got '" + text + "'");
    out.push_back(static_cast<int>(n));
    begin = comma + 1;
  }
  return out;
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace weft::cli
