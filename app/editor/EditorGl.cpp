#include "EditorGl.h"

#include <weft/render/RenderContext.h>
#include <weft/render/RenderError.h>

#include <string>

WeftEditorGl weftEditorGl{};

namespace weft::editor {

void loadEditorGl(render::RenderContext& context) {
  context.makeCurrent();
  WeftEditorGl table{};
#define WEFT_EDITOR_GL_LOAD(type, name)                                    \
  table.name = reinterpret_cast<type>(context.getProcAddress("gl" #name)); \
  if (!table.name)                                                         \
    throw render::ContextError("the " + context.backendName() + " context lacks gl" #name);
  WEFT_EDITOR_GL_FUNCTIONS(WEFT_EDITOR_GL_LOAD)
#undef WEFT_EDITOR_GL_LOAD
  weftEditorGl = table;
}

}  // namespace weft::editor
