#include "Autosave.h"

#include <weft/io/AtomicFile.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>

namespace weft::editor {
namespace fs = std::filesystem;
namespace {

// FNV-1a, 64 bits: a stable name for a path, the same in every run.
std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t h = 14695981039346656037ULL;
  for (unsigned char c : text) h = (h ^ c) * 1099511628211ULL;
  return h;
}

std::string utcNow() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

}  // namespace

Autosave::Autosave(std::string folder, double interval)
    : folder_(std::move(folder)), interval_(interval) {}

std::string Autosave::defaultFolder() {
  const char* state = std::getenv("XDG_STATE_HOME");
  const char* home = std::getenv("HOME");
  const fs::path base =
      state && *state ? fs::path(state) : fs::path(home ? home : ".") / ".local" / "state";
  return (base / "weft" / "recovery").string();
}

std::string Autosave::fileFor(const std::string& sceneFile) const {
  std::error_code ec;
  const std::string absolute =
      sceneFile.empty() ? "" : fs::absolute(sceneFile, ec).lexically_normal().string();
  const std::string stem = sceneFile.empty() ? "untitled" : fs::path(sceneFile).stem().string();
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(fnv1a(absolute)));
  return (fs::path(folder_) / (stem + "-" + hash + ".json")).string();
}

bool Autosave::pending(const EditorDocument& document) const {
  return enabled() && document.dirty() && document.revision() != writtenRevision_;
}

void Autosave::tick(const EditorDocument& document, double seconds) {
  if (!enabled()) return;
  sinceWrite_ += seconds;
  // Nothing written and nothing to write: the common idle case, no path work per frame.
  if (written_.empty() && !document.dirty()) return;
  const std::string target = fileFor(document.file());
  std::error_code ec;
  if (!written_.empty() && (!document.dirty() || written_ != target)) {
    fs::remove(written_, ec);  // saved, undone to the saved state, or another file now
    written_.clear();
    writtenRevision_ = -1;
  }
  if (!pending(document) || sinceWrite_ < interval_) return;
  std::error_code made;
  fs::create_directories(folder_, made);
  std::error_code absoluteError;
  const std::string scene =
      document.file().empty()
          ? ""
          : fs::absolute(document.file(), absoluteError).lexically_normal().string();
  const nlohmann::json record = {
      {"scene_file", scene}, {"saved_at", utcNow()}, {"document", document.document()}};
  try {
    writeFileAtomically(target, record.dump(1) + "\n");
    written_ = target;
    writtenRevision_ = document.revision();
    sinceWrite_ = 0.0;
    error_.clear();
  } catch (const std::exception& e) {
    error_ = e.what();
    writtenRevision_ = document.revision();  // not again for this revision
    sinceWrite_ = 0.0;
  }
}

void Autosave::discardCurrent() {
  if (written_.empty()) return;
  std::error_code ec;
  fs::remove(written_, ec);
  written_.clear();
  writtenRevision_ = -1;
}

std::vector<Recovery> Autosave::recoveries() const {
  std::vector<Recovery> out;
  if (!enabled()) return out;
  std::error_code ec;
  for (fs::directory_iterator it(folder_, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().extension() != ".json" || it->path().string() == written_) continue;
    std::ifstream in(it->path());
    try {
      const nlohmann::json record = nlohmann::json::parse(in);
      if (!record.contains("document") || !record["document"].is_object()) continue;
      out.push_back({it->path().string(), record.value("scene_file", ""),
                     record.value("saved_at", ""), record["document"]});
    } catch (const std::exception&) {
      continue;  // a damaged file is not offered
    }
  }
  std::sort(out.begin(), out.end(),
            [](const Recovery& a, const Recovery& b) { return a.savedAt > b.savedAt; });
  return out;
}

void Autosave::remove(const Recovery& recovery) {
  std::error_code ec;
  fs::remove(recovery.path, ec);
}

}  // namespace weft::editor
