#include "cellforge/topo/validate.h"

#include "topo/validate_checks.h"

namespace cellforge::inline topo {

std::vector<Violation> validate(const Model& m) {
  std::vector<Violation> out;
  checks::records(m, out);
  if (!out.empty()) return out;  // the walks below would follow dangling references
  checks::groups(m, out);
  checks::vertex_cycles(m, out);
  checks::radial_cycles(m, out);
  checks::loops(m, out);
  if (!out.empty()) return out;
  checks::face_marks(m, out);
  checks::wedges(m, out);
  checks::euler(m, out);
  return out;
}

std::string to_string(const std::vector<Violation>& violations) {
  std::string s;
  for (const Violation& v : violations) s += "[" + v.check + "] " + v.message + "\n";
  return s;
}

}  // namespace cellforge::inline topo
