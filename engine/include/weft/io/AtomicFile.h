#pragma once
// Whole-file writes that a crash or a kill cannot leave half done (the editor's Save, the
// applications benchmark's stored runs).

#include <string>

namespace weft {

// Writes `text` to `path` atomically: a temporary file in the same folder, flushed to disk and
// closed, then renamed over `path` (keeping the replaced file's permissions). Throws InputError
// naming the path on failure (the temporary file is removed, the target untouched).
void writeFileAtomically(const std::string& path, const std::string& text);

}  // namespace weft
