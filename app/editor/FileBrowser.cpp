#include "FileBrowser.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <system_error>

namespace weft::editor {
namespace fs = std::filesystem;
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool byName(const FileEntry& a, const FileEntry& b) {
  const std::string la = lower(a.name), lb = lower(b.name);
  return la != lb ? la < lb : a.name < b.name;
}

fs::path normalFolder(const fs::path& folder) {
  std::error_code ec;
  fs::path absolute = fs::absolute(folder, ec).lexically_normal();
  // "/a/b/" normalises to "/a/b/": the empty last part is dropped so parent_path() goes up.
  if (absolute.has_relative_path() && absolute.filename().empty())
    absolute = absolute.parent_path();
  return absolute;
}

}  // namespace

FileBrowser::FileBrowser(std::vector<std::string> extensions)
    : extensions_(std::move(extensions)) {}

bool FileBrowser::lists(const std::string& fileName) const {
  if (extensions_.empty()) return true;
  const std::string ext = lower(fs::path(fileName).extension().string());
  return std::find(extensions_.begin(), extensions_.end(), ext) != extensions_.end();
}

bool FileBrowser::show(const fs::path& folder) {
  const fs::path target = normalFolder(folder);
  std::error_code ec;
  fs::directory_iterator it(target, fs::directory_options::skip_permission_denied, ec);
  if (ec) {
    error_ = target.string() + ": " + ec.message();
    return false;
  }
  std::vector<FileEntry> folders, files;
  for (const fs::directory_iterator end; it != end; it.increment(ec)) {
    if (ec) break;
    const std::string name = it->path().filename().string();
    if (name.empty() || name[0] == '.') continue;  // hidden
    std::error_code statusError;
    if (it->is_directory(statusError))
      folders.push_back({name, true});
    else if (!statusError && lists(name))
      files.push_back({name, false});
  }
  if (ec) {
    error_ = target.string() + ": " + ec.message();
    return false;
  }
  std::sort(folders.begin(), folders.end(), byName);
  std::sort(files.begin(), files.end(), byName);
  if (target != folder_) picked_.clear();
  folder_ = target;
  entries_.clear();
  if (target.has_relative_path()) entries_.push_back({"..", true});
  entries_.insert(entries_.end(), folders.begin(), folders.end());
  entries_.insert(entries_.end(), files.begin(), files.end());
  error_.clear();
  return true;
}

bool FileBrowser::showFolderOf(const std::string& path) {
  if (path.empty()) return false;
  std::error_code ec;
  if (fs::is_directory(path, ec)) return show(path);
  const fs::path parent = normalFolder(path).parent_path();
  return fs::is_directory(parent, ec) && show(parent);
}

bool FileBrowser::enter(const FileEntry& entry) {
  if (!entry.folder) return false;
  return entry.name == ".." ? up() : show(folder_ / entry.name);
}

bool FileBrowser::up() {
  return folder_.has_relative_path() && show(folder_.parent_path());
}

void FileBrowser::refresh() {
  if (!folder_.empty()) show(folder_);
}

std::string FileBrowser::pathOf(const FileEntry& entry) const {
  return entry.name == ".." ? folder_.parent_path().string() : (folder_ / entry.name).string();
}

std::vector<std::string> browsePlaces(const std::string& sceneFile,
                                      const std::vector<std::string>& recentFiles) {
  std::vector<std::string> places;
  const auto add = [&](const fs::path& folder) {
    std::error_code ec;
    if (folder.empty() || !fs::is_directory(folder, ec)) return;
    const std::string normal = normalFolder(folder).string();
    if (std::find(places.begin(), places.end(), normal) == places.end()) places.push_back(normal);
  };
  std::error_code ec;
  add(fs::current_path(ec));
  if (!sceneFile.empty()) add(normalFolder(sceneFile).parent_path());
  for (const std::string& f : recentFiles) add(normalFolder(f).parent_path());
  if (const char* home = std::getenv("HOME"); home && *home) add(home);
  return places;
}

}  // namespace weft::editor
