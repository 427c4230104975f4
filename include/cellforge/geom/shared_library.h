// A shared library opened when first needed (dlopen) and its functions looked up by
// name: for dependencies that few runs use and that, linked, every run would load at
// start (store/'s libpq, csg/'s FreeType, HarfBuzz and fontconfig).
#pragma once

#include <string>

namespace cellforge::inline geom {

class SharedLibrary {
 public:
  // Opens `soname` (RTLD_NOW | RTLD_LOCAL; never closed); `problems` says why not.
  explicit SharedLibrary(const char* soname);
  // The function `name`, or nullptr (noted in `problems`; nullptr for all when the
  // library did not open).
  void* symbol(const char* name);
  // What went wrong, "; "-separated; empty when everything asked for was found.
  const std::string& problems() const { return problems_; }

 private:
  void* handle_ = nullptr;
  std::string soname_, problems_;
};

}  // namespace cellforge::inline geom
