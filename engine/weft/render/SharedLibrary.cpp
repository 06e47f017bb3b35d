#include <weft/render/SharedLibrary.h>

#include <weft/render/RenderError.h>

#include <dlfcn.h>

#include <cstdlib>

namespace weft::render {

SharedLibrary::SharedLibrary(const std::vector<std::string>& names) {
  std::string reasons;
  for (const std::string& n : names) {
    // RTLD_LOCAL: the library's gl* symbols must not become visible to other libraries.
    handle_ = ::dlopen(n.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle_) {
      name_ = n;
      return;
    }
    const char* e = ::dlerror();
    reasons += (reasons.empty() ? "" : "; ") + std::string(e ? e : n + ": cannot open");
  }
  throw ContextError(reasons);
}

SharedLibrary::~SharedLibrary() {
  if (handle_) ::dlclose(handle_);
}

void* SharedLibrary::symbol(const char* name) const {
  return ::dlsym(handle_, name);
}

void* SharedLibrary::required(const char* name) const {
  void* s = symbol(name);
  if (!s) throw ContextError(name_ + ": missing symbol " + name);
  return s;
}

std::vector<std::string> libraryNames(const char* variable, std::vector<std::string> defaults) {
  const char* chosen = std::getenv(variable);
  if (chosen && *chosen) return {chosen};
  return defaults;
}

}  // namespace weft::render
