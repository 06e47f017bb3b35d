#pragma once
// A fresh folder under the system temp directory for one test's generated files (meshes,
// scenes, run outputs), so nothing is ever written into the source tree. Removed on
// destruction unless WEFT_KEEP_TEST_FILES is set (to inspect a failure).

#include <string>

namespace weft::test {

class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::string& path() const { return path_; }
  std::string file(const std::string& name) const { return path_ + "/" + name; }
  // Writes `text` to `name` inside the folder and returns its full path.
  std::string write(const std::string& name, const std::string& text) const;

 private:
  std::string path_;
};

// Whole file as a string (binary-safe); fails the current test if it cannot be read.
std::string readFile(const std::string& path);

// Absolute path of a file under tests/data.
std::string dataFile(const std::string& relative);

}  // namespace weft::test
