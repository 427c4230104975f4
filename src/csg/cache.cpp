#include "cache.h"

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cellforge/io/mesh_io.h"

namespace cellforge::csg {

bool DiskCache::load(const std::string& key, Model& m, std::vector<FaceColor>& colors) const {
  if (dir_.empty()) return false;
  const std::string base = dir_ + "/" + key;
  std::ifstream c(base + ".colors");
  if (!c) return false;
  Model read;
  if (!io::read_file(read, base + ".json")) return false;
  colors.assign(read.face_slots(), std::nullopt);
  std::string line;
  for (FaceId f : read.faces()) {
    if (!std::getline(c, line)) return false;
    if (line == "-") continue;
    std::array<double, 4> rgba{};
    std::istringstream s(line);
    if (!(s >> rgba[0] >> rgba[1] >> rgba[2] >> rgba[3])) return false;
    colors[f.value] = rgba;
  }
  m = std::move(read);
  return true;
}

void DiskCache::store(const std::string& key, const Model& m,
                      const std::vector<FaceColor>& colors) const {
  if (dir_.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  const std::string base = dir_ + "/" + key;
  // Unique to the process and the call: parts are stored from several threads.
  static std::atomic<unsigned> calls{0};
  const std::string tmp = "." + std::to_string(::getpid()) + "-" + std::to_string(calls++);
  auto bytes = io::write_model(m, io::Format::kJson);
  if (!bytes) return;
  {
    std::ofstream out(base + ".json" + tmp, std::ios::binary);
    out << *bytes;
    if (!out) return;
  }
  {
    std::ofstream out(base + ".colors" + tmp);
    char buf[128];
    for (FaceId f : m.faces()) {
      const FaceColor& col = f.value < colors.size() ? colors[f.value] : FaceColor{};
      if (col) {
        std::snprintf(buf, sizeof buf, "%.17g %.17g %.17g %.17g", (*col)[0], (*col)[1], (*col)[2],
                      (*col)[3]);
        out << buf << '\n';
      } else {
        out << "-\n";
      }
    }
    if (!out) return;
  }
  std::filesystem::rename(base + ".json" + tmp, base + ".json", ec);
  if (!ec) std::filesystem::rename(base + ".colors" + tmp, base + ".colors", ec);
}

}  // namespace cellforge::csg
