// Typed 32-bit handles for the topology entities. Each is invalid by default and
// prints with a one-letter prefix: v12 (vertex), e7 (edge), u3 (edge use),
// l2 (loop), f5 (face), c1 (volume, a 3-cell), g0 (group).
#pragma once

#include <compare>
#include <cstdint>
#include <functional>
#include <ostream>
#include <string>

namespace cellforge {

inline constexpr std::uint32_t kInvalidIndex = 0xFFFFFFFFu;

template <class Tag>
struct Id {
  std::uint32_t value = kInvalidIndex;

  constexpr Id() = default;
  constexpr explicit Id(std::uint32_t v) : value(v) {}
  constexpr bool is_valid() const { return value != kInvalidIndex; }
  friend constexpr auto operator<=>(Id, Id) = default;

  std::string str() const {
    return is_valid() ? Tag::kPrefix + std::to_string(value) : std::string(Tag::kPrefix) + "?";
  }
  friend std::ostream& operator<<(std::ostream& os, Id id) { return os << id.str(); }
};

struct VertexTag {
  static constexpr const char* kPrefix = "v";
};
struct EdgeTag {
  static constexpr const char* kPrefix = "e";
};
struct EdgeUseTag {
  static constexpr const char* kPrefix = "u";
};
struct LoopTag {
  static constexpr const char* kPrefix = "l";
};
struct FaceTag {
  static constexpr const char* kPrefix = "f";
};
struct VolumeTag {
  static constexpr const char* kPrefix = "c";
};
struct GroupTag {
  static constexpr const char* kPrefix = "g";
};

using VertexId = Id<VertexTag>;
using EdgeId = Id<EdgeTag>;
using EdgeUseId = Id<EdgeUseTag>;
using LoopId = Id<LoopTag>;
using FaceId = Id<FaceTag>;
using VolumeId = Id<VolumeTag>;
using GroupId = Id<GroupTag>;

}  // namespace cellforge

template <class Tag>
struct std::hash<cellforge::Id<Tag>> {
  std::size_t operator()(cellforge::Id<Tag> id) const noexcept { return id.value; }
};
