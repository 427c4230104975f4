// libFuzzer target for one reader of io/ (built once per format by scripts/fuzz.sh
// with -DFUZZ_FORMAT=kStl, kObj, kOff, k3mf or kJson). Any input must end in a
// model or an error; small models read are also diagnosed and written back, so
// the import, triangulation and writers see what the parsers let through.
#include <cstddef>
#include <cstdint>

#include "cellforge/io/diagnose.h"
#include "cellforge/io/mesh_io.h"

#ifndef FUZZ_FORMAT
#error "build with -DFUZZ_FORMAT=kStl (or kObj, kOff, k3mf, kJson)"
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace cellforge;
  constexpr io::Format kFormat = io::Format::FUZZ_FORMAT;
  io::ReadOptions options;
  // Vary the import options with the input's last byte.
  const std::uint8_t knobs = size ? data[size - 1] : 0;
  options.import.merge_coplanar = knobs & 1;
  options.import.repair_orientation = knobs & 2;
  options.import.weld_tolerance = (knobs & 4) ? 1e-3 : 0;
  Model m;
  auto r = io::read_model(m, {data, size}, kFormat, options);
  if (!r.ok() || m.num_faces() > 2000) return 0;
  (void)io::diagnose(m);
  for (io::Format f : {io::Format::kStl, io::Format::kObj, io::Format::kJson}) {
    auto bytes = io::write_model(m, f);
    if (!bytes.ok()) __builtin_trap();  // every model read can be written
  }
  return 0;
}
