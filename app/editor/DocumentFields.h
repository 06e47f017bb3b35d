#pragma once
// Dear ImGui widgets bound to a JSON path of the document: each change is one document edit,
// and consecutive changes of the same item (typing, dragging) merge into one undo step. A
// refused edit is shown as the app's message. `fallback` is shown when the key is absent.

#include <string>

namespace weft::editor {

class EditorApp;
class EditorSession;

class DocumentFields {
 public:
  DocumentFields(EditorSession& session, EditorApp& app) : session_(session), app_(app) {}

  bool number(const char* label, const std::string& path, double fallback,
              const char* format = "%.6g");
  bool integer(const char* label, const std::string& path, int fallback);
  bool vector(const char* label, const std::string& path, const double* fallback);
  void combo(const char* label, const std::string& path, const char* const* options, int count,
             const char* fallback);
  // A text field (e.g. a pin group's name); `hint` shows greyed while it is empty.
  bool text(const char* label, const std::string& path, const char* hint);
  // Reports an edit's error; `field` is the document path of the field that made it ("" for
  // none), whose next change merges into the same undo step.
  void apply(const std::string& error, const std::string& field = "");

 private:
  // Tells the app where the item just drawn for `path` lies (scripts click fields by path).
  void noteItem(const std::string& path);
  template <class Value, class Widget>
  bool field(const std::string& path, Value value, Widget&& widget);

  EditorSession& session_;
  EditorApp& app_;
  std::string lastEditField_;  // path of the field that made the last document edit (coalescing)
};

}  // namespace weft::editor
