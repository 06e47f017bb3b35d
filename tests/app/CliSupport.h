#pragma once
// Running the real `weft` binary and reading what it writes, independently of the engine's own
// readers (the .npy header and CSV are parsed here from the bytes).

#include <support/Process.h>
#include <support/TempDir.h>

#include <gtest/gtest.h>

#include <cstring>
#include <sstream>
#include <string>
#include <vector>

namespace weft::test {

inline ProcessResult runWeft(const std::vector<std::string>& args,
                             const std::string& workDir = "") {
  std::vector<std::string> argv{WEFT_BINARY};
  argv.insert(argv.end(), args.begin(), args.end());
  return runProcess(argv, workDir);
}

// Everything printed, for failure messages.
inline std::string describe(const ProcessResult& r) {
  return "exit " + std::to_string(r.exitCode) +
         (r.signal ? " (signal " + std::to_string(r.signal) + ")" : "") + "\n--- stdout\n" + r.out +
         "--- stderr\n" + r.err;
}

// Runs `weft VERB args...` and expects a clean bad-input failure: exit 2 and one
// `error: ...` message naming `where` and `phrase`. The caller then checks what must be left
// untouched (no stdout, an old output folder).
inline ProcessResult expectBadInput(const std::string& verb, const std::vector<std::string>& args,
                                    const std::string& where, const std::string& phrase) {
  std::vector<std::string> all{verb};
  all.insert(all.end(), args.begin(), args.end());
  ProcessResult r = runWeft(all);
  EXPECT_EQ(r.exitCode, 2) << describe(r);
  EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(where), std::string::npos) << "expected '" << where << "' in: " << r.err;
  EXPECT_NE(r.err.find(phrase), std::string::npos) << "expected '" << phrase << "' in: " << r.err;
  return r;
}

struct ParsedNpy {
  int major = 0, minor = 0;
  std::size_t dataOffset = 0;
  std::string header;
  std::vector<std::size_t> shape;
  std::vector<double> data;
};

// Parses a format 1.x little-endian float64 .npy file, asserting on every structural rule.
inline ParsedNpy parseNpy(const std::string& bytes) {
  ParsedNpy npy;
  EXPECT_GE(bytes.size(), 10u);
  if (bytes.size() < 10) return npy;
  EXPECT_EQ(bytes.substr(0, 6), "\x93NUMPY");
  npy.major = bytes[6];
  npy.minor = bytes[7];
  const std::size_t length =
      static_cast<unsigned char>(bytes[8]) | (static_cast<unsigned char>(bytes[9]) << 8);
  npy.dataOffset = 10 + length;
  EXPECT_LE(npy.dataOffset, bytes.size());
  npy.header = bytes.substr(10, length);
  EXPECT_NE(npy.header.find("'descr': '<f8'"), std::string::npos) << npy.header;
  EXPECT_NE(npy.header.find("'fortran_order': False"), std::string::npos) << npy.header;
  const auto open = npy.header.find("'shape': (");
  const auto close = npy.header.find(')', open);
  EXPECT_NE(open, std::string::npos) << npy.header;
  if (open == std::string::npos || close == std::string::npos) return npy;
  std::stringstream dims(npy.header.substr(open + 10, close - open - 10));
  std::string item;
  while (std::getline(dims, item, ','))
    if (item.find_first_of("0123456789") != std::string::npos)
      npy.shape.push_back(std::stoul(item));
  std::size_t count = 1;
  for (std::size_t d : npy.shape) count *= d;
  EXPECT_EQ(bytes.size() - npy.dataOffset, count * sizeof(double)) << "payload size";
  if (bytes.size() - npy.dataOffset != count * sizeof(double)) return npy;
  npy.data.resize(count);
  std::memcpy(npy.data.data(), bytes.data() + npy.dataOffset, count * sizeof(double));
  return npy;
}

inline std::vector<std::string> splitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream s(text);
  std::string line;
  while (std::getline(s, line)) lines.push_back(line);
  return lines;
}

inline std::vector<std::string> splitCommas(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream s(line);
  std::string field;
  while (std::getline(s, field, ',')) fields.push_back(field);
  return fields;
}

// Header and data rows of a CSV a benchmark wrote.
inline std::vector<std::vector<std::string>> readCsv(const std::string& path) {
  std::vector<std::vector<std::string>> rows;
  for (const std::string& line : splitLines(readFile(path))) rows.push_back(splitCommas(line));
  return rows;
}

}  // namespace weft::test
