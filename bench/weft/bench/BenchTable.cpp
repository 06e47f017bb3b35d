#include "BenchTable.h"

#include <weft/core/Error.h>

#include <sys/utsname.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <thread>

namespace weft::bench {

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

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace weft::bench
