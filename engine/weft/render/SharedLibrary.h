#pragma once
// A shared library opened at run time. The headless backends open libOSMesa and libEGL this
// way so that `weft` starts (and every other verb works) on a machine without them, and a
// missing library becomes a clear error when rendering is asked for.

#include <string>
#include <vector>

namespace weft::render {

class SharedLibrary {
 public:
  // Opens the first of `names` that loads; throws ContextError listing why each failed.
  explicit SharedLibrary(const std::vector<std::string>& names);
  ~SharedLibrary();
  SharedLibrary(const SharedLibrary&) = delete;
  SharedLibrary& operator=(const SharedLibrary&) = delete;

  void* symbol(const char* name) const;  // null when absent
  // The symbol as a function pointer; throws ContextError when absent.
  template <class Function>
  Function function(const char* name) const {
    return reinterpret_cast<Function>(required(name));
  }
  const std::string& name() const { return name_; }

 private:
  void* required(const char* name) const;
  void* handle_ = nullptr;
  std::string name_;
};

// `defaults`, or only the library named by the environment variable `variable` when it is set:
// a way to pick a specific build, and for tests to stand in for a machine that lacks one.
std::vector<std::string> libraryNames(const char* variable, std::vector<std::string> defaults);

// In a sanitizer build (WEFT_SANITIZE), keeps every shared library mapped now mapped until the
// process exits, including those a GL library opened itself (Mesa's DRI driver, closed again by
// eglTerminate and glfwTerminate): LeakSanitizer runs at exit and needs their globals, which
// still point to what they allocated, and their names for its stacks. Otherwise does nothing.
void keepLoadedLibrariesForSanitizers();

}  // namespace weft::render
