#pragma once
// What the editor's file dialogs browse, without drawing it: the folder shown and its entries
// (the parent first, then folders, then the files the dialog can use, each group in
// case-insensitive name order; hidden entries left out), moving between folders, and the places
// to start from (the working directory, the scene's folder, the folders of recent scenes, home).
// FileBrowserView draws it. No window: unit tested.

#include <filesystem>
#include <string>
#include <vector>

namespace weft::editor {

struct FileEntry {
  std::string name;  // ".." for the parent folder
  bool folder = false;
};

class FileBrowser {
 public:
  // `extensions`: the endings of the files listed, lower case with the dot (".obj"); empty lists
  // every file.
  explicit FileBrowser(std::vector<std::string> extensions = {});

  // Shows `folder` (made absolute and normal). When it cannot be listed, returns false and keeps
  // showing what it showed, with error() saying why.
  bool show(const std::filesystem::path& folder);
  // Shows the folder a path field names: the folder itself, or the one holding the file (which
  // need not exist yet, as in Save As). False when neither exists.
  bool showFolderOf(const std::string& path);
  // A folder entry (or ".."): shows it. False for a file entry or a folder that cannot be listed.
  bool enter(const FileEntry& entry);
  bool up();
  // Lists the folder again (after a save, or files appearing).
  void refresh();

  const std::filesystem::path& folder() const { return folder_; }
  const std::vector<FileEntry>& entries() const { return entries_; }
  const std::string& error() const { return error_; }
  // The absolute path of an entry of the folder shown.
  std::string pathOf(const FileEntry& entry) const;
  // Whether the dialog can use a file of this name (its extension is one listed).
  bool lists(const std::string& fileName) const;

  // The file last picked with a click (its absolute path), "" after moving to another folder: a
  // double click confirms only the file its first click picked, so the second click of a double
  // click that opened a folder cannot confirm whatever the new listing puts under the mouse.
  const std::string& picked() const { return picked_; }
  void pick(const FileEntry& entry) { picked_ = entry.folder ? std::string() : pathOf(entry); }

 private:
  std::vector<std::string> extensions_;
  std::filesystem::path folder_;
  std::vector<FileEntry> entries_;
  std::string error_;
  std::string picked_;
};

// Folders to start browsing from, without duplicates, in this order: the working directory, the
// scene's folder (when the scene has a file), the folders of the recent scene files (most recent
// first), the home folder. Folders that no longer exist are left out.
std::vector<std::string> browsePlaces(const std::string& sceneFile,
                                      const std::vector<std::string>& recentFiles);

}  // namespace weft::editor
