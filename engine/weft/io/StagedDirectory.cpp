#include <weft/io/StagedDirectory.h>

#include <weft/core/Error.h>

#include <unistd.h>

#include <filesystem>
#include <system_error>

namespace fs = std::filesystem;

namespace weft {

StagedDirectory::StagedDirectory(std::string finalPath) : final_(std::move(finalPath)) {
  while (final_.size() > 1 && final_.back() == '/') final_.pop_back();
  if (final_.empty()) throw InputError("<command line>", "--out", "empty output path");
  std::error_code ec;
  if (fs::exists(final_, ec) && !fs::is_directory(final_, ec))
    throw InputError("<command line>", "--out", final_ + " exists and is not a folder");
  const fs::path parent = fs::absolute(final_).parent_path();
  fs::create_directories(parent, ec);
  if (ec)
    throw InputError("<command line>", "--out",
                     "cannot create " + parent.string() + ": " + ec.message());
  staging_ = final_ + ".tmp-" + std::to_string(::getpid());
  fs::remove_all(staging_, ec);
  fs::create_directory(staging_, ec);
  if (ec)
    throw InputError("<command line>", "--out", "cannot create " + staging_ + ": " + ec.message());
}

StagedDirectory::~StagedDirectory() {
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(staging_, ec);
  }
}

void StagedDirectory::commit() {
  std::error_code ec;
  const std::string old = final_ + ".old-" + std::to_string(::getpid());
  const bool hadOld = fs::exists(final_, ec);
  if (hadOld) {
    fs::rename(final_, old, ec);
    if (ec)
      throw InputError("<command line>", "--out", "cannot replace " + final_ + ": " + ec.message());
  }
  fs::rename(staging_, final_, ec);
  if (ec) {
    if (hadOld) fs::rename(old, final_, ec);
    throw InputError("<command line>", "--out", "cannot move output into " + final_);
  }
  committed_ = true;
  if (hadOld) fs::remove_all(old, ec);
}

}  // namespace weft
