// Uses the installed library through <cellforge/cellforge.h> alone: builds a cube,
// checks it, writes it as STL and reads it back. Exits 0 when every check holds.
#include <cellforge/cellforge.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

namespace {

int failures = 0;

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "consumer: %s failed\n", what);
    ++failures;
  }
}

}  // namespace

int main() {
  using namespace cellforge;
  Model m;
  const auto cube = shape::make_cube(m, {.size = {2, 3, 4}});
  check(static_cast<bool>(cube), "make_cube");
  check(validate(m).empty(), "validate");
  check(m.num_vertices() == 8 && m.num_edges() == 12 && m.num_faces() == 6, "counts");
  check(std::fabs(shape::mass_properties(m).volume - 24) < 1e-12, "volume");
  check(orient3d({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}) == 1, "orient3d");

  const auto stl = io::write_model(m, io::Format::kStl);
  check(static_cast<bool>(stl), "write_model");
  if (stl) {
    std::vector<std::uint8_t> bytes(stl->size());
    std::memcpy(bytes.data(), stl->data(), bytes.size());
    Model back;
    const auto read =
        io::read_model(back, bytes, io::Format::kStl, {.import = {.merge_coplanar = true}});
    check(static_cast<bool>(read), "read_model");
    check(back.num_faces() == 6 && back.num_volumes() == 1 && validate(back).empty(),
          "the STL read back is the cube");
  }
  if (failures == 0)
    std::printf("consumer: cellforge %s works from its installed package\n", CELLFORGE_VERSION);
  return failures == 0 ? 0 : 1;
}
