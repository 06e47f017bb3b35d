#pragma once
// A measured table as `weft bench` writes it: CSV (all columns), Markdown (for docs) and a PNG
// plot drawn by gnuplot (Debian's gnuplot-nox) when it is installed.

#include <ostream>
#include <string>
#include <vector>

namespace weft::bench {

class BenchTable {
 public:
  explicit BenchTable(std::vector<std::string> columns) : columns_(std::move(columns)) {}
  void add(std::vector<std::string> row) { rows_.push_back(std::move(row)); }
  const std::vector<std::vector<std::string>>& rows() const { return rows_; }
  void writeCsv(const std::string& path) const;
  void writeMarkdown(const std::string& path, const std::string& title,
                     const std::string& preamble) const;
  // The same section into a stream, for a Markdown file holding several tables.
  void writeMarkdown(std::ostream& out, const std::string& title,
                     const std::string& preamble) const;

 private:
  std::vector<std::string> columns_;
  std::vector<std::vector<std::string>> rows_;
};

// The median of a measured sample (0 for an empty one): the middle element, the upper one of
// the two middle elements for an even count.
double median(std::vector<double> values);

// One plotted series: x/y columns of a CSV data block, drawn in a gnuplot style ("steps" for a
// running minimum).
struct PlotSeries {
  std::string title;
  std::vector<double> x, y;
  std::string style = "linespoints";
};

// Writes `png` with gnuplot (log-log when asked). Returns false, with a reason, when gnuplot is
// missing or fails; the CSV and Markdown are still written by the caller.
bool plotSeries(const std::string& png, const std::string& title, const std::string& xLabel,
                const std::string& yLabel, const std::vector<PlotSeries>& series, bool logX,
                bool logY, std::string& reason);

std::string formatNumber(double v, int precision = 4);
// "Linux x86_64, 2 cores, <cpu model>" for the record of where a benchmark ran.
std::string machineDescription();

}  // namespace weft::bench
