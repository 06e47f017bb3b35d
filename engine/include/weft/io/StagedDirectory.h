#pragma once
#include <string>

namespace weft {

// An output folder that appears only when complete: files are written into a sibling
// temporary folder, and commit() swaps it into place. If the run fails before commit(), the
// temporary folder is removed and an existing output folder is left untouched.
class StagedDirectory {
 public:
  explicit StagedDirectory(std::string finalPath);
  ~StagedDirectory();
  StagedDirectory(const StagedDirectory&) = delete;
  StagedDirectory& operator=(const StagedDirectory&) = delete;

  const std::string& path() const { return staging_; }  // where to write now
  std::string file(const std::string& name) const { return staging_ + "/" + name; }
  void commit();

 private:
  std::string final_, staging_;
  bool committed_ = false;
};

}  // namespace weft
