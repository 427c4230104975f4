// The on-disk cache of built subtrees (private to csg/): a model and its face colors
// under the subtree's content key, in a folder. Files are written to a temporary
// name and renamed, so a reader never sees half a file; an unreadable entry is a miss.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "cellforge/topo/model.h"

namespace cellforge::csg {

using FaceColor = std::optional<std::array<double, 4>>;

class DiskCache {
 public:
  explicit DiskCache(std::string dir) : dir_(std::move(dir)) {}
  bool enabled() const { return !dir_.empty(); }
  // colors come back by result FaceId value.
  bool load(const std::string& key, Model& m, std::vector<FaceColor>& colors) const;
  void store(const std::string& key, const Model& m, const std::vector<FaceColor>& colors) const;

 private:
  std::string dir_;
};

}  // namespace cellforge::csg
