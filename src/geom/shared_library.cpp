// geom/shared_library.h.
#include "cellforge/geom/shared_library.h"

#include <dlfcn.h>

namespace cellforge::inline geom {

SharedLibrary::SharedLibrary(const char* soname) : soname_(soname) {
  handle_ = dlopen(soname, RTLD_NOW | RTLD_LOCAL);
  if (handle_ == nullptr) problems_ = std::string("cannot load ") + soname + ": " + dlerror();
}

void* SharedLibrary::symbol(const char* name) {
  if (handle_ == nullptr) return nullptr;
  void* f = dlsym(handle_, name);
  if (f == nullptr) problems_ += (problems_.empty() ? "" : "; ") + soname_ + " lacks " + name;
  return f;
}

}  // namespace cellforge::inline geom
