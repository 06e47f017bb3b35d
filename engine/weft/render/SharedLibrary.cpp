#include <weft/render/SharedLibrary.h>

#include <weft/render/RenderError.h>

#include <dlfcn.h>
#include <link.h>

#include <cstdlib>

namespace weft::render {

namespace {
#ifdef WEFT_SANITIZER_BUILD
// Under the sanitizers (WEFT_SANITIZE) the library stays mapped after dlclose, so the stacks of
// what LeakSanitizer reports at exit still resolve to the library's frames.
constexpr int kOpenFlags = RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE;
#else
constexpr int kOpenFlags = RTLD_NOW | RTLD_LOCAL;
#endif
}  // namespace

SharedLibrary::SharedLibrary(const std::vector<std::string>& names) {
  std::string reasons;
  for (const std::string& n : names) {
    // RTLD_LOCAL: the library's gl* symbols must not become visible to other libraries.
    handle_ = ::dlopen(n.c_str(), kOpenFlags);
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

void keepLoadedLibrariesForSanitizers() {
#ifdef WEFT_SANITIZER_BUILD
  std::vector<std::string> loaded;
  ::dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void* names) {
        if (info->dlpi_name && *info->dlpi_name)
          static_cast<std::vector<std::string>*>(names)->push_back(info->dlpi_name);
        return 0;
      },
      &loaded);
  // RTLD_NOLOAD opens nothing new; it adds RTLD_NODELETE to a library already loaded.
  for (const std::string& name : loaded)
    ::dlopen(name.c_str(), RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
#endif
}

}  // namespace weft::render
