// import() of SVG (import2d.h).
#include "import2d.h"

namespace cellforge::csg {

Result<std::vector<std::vector<Vec2>>> read_svg(const std::string& path, const Import2DOptions&) {
  return Error{ErrorCode::kUnsupported, path + ": import() of SVG is not supported yet"};
}

}  // namespace cellforge::csg
