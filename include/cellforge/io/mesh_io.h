// Reading and writing models: STL (ASCII and binary), OBJ, OFF, 3MF and the native
// JSON format (docs/io.md).
//
// Mesh formats are read in two steps: a parser turns the bytes into an indexed
// polygon soup (positions, polygons, wires, points), and import() welds the
// positions and builds the soup into one new group through build_mesh. The native
// JSON format is lossless and bypasses the soup: it restores the model's tables
// (topo/snapshot.h, property tables of the stored value types included) exactly,
// and keeps attachments beside the model.
//
// Errors name where the input went wrong: "line 12:7" for text, "byte 184" for
// binary data. No parser allocates from a count it has not checked against the
// size of the input.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cellforge/result.h"
#include "cellforge/topo/attachment.h"
#include "cellforge/topo/model.h"
#include "cellforge/topo/property.h"

namespace cellforge::io {

enum class Format { kStl, kObj, kOff, k3mf, kJson };

// "stl", "obj", "off", "3mf", "json".
std::string_view format_name(Format f);
// From a file name's extension (case-insensitive); an error names the extension.
Result<Format> format_from_path(std::string_view path);
// Whether this build can read and write 3MF (always, since io/ reads and writes it
// itself; kept for callers written when 3MF depended on lib3mf).
bool has_3mf();

// What a mesh parser produces: polygons as index cycles into `positions` (a
// polygon with holes comes only from formats that have them), wire edges and
// isolated points. Indices are checked against positions by the parser.
struct PolygonSoup {
  std::vector<Vec3> positions;
  std::vector<std::vector<std::uint32_t>> polygons;
  std::vector<std::array<std::uint32_t, 2>> wires;
  std::vector<std::uint32_t> points;
  std::string name;  // a name the file gives its object, if any
  // A colour per polygon when the file gives any (OFF's face colours; polygons
  // without one are white), else empty.
  std::vector<Colour> colours;
};

// The face properties import_soup fills (property.h): "source_polygon" (std::uint32_t)
// is the index in the soup of the polygon a face was made from (the first one of a
// merged coplanar patch); "colour" (Colour) that polygon's colour, when the soup has
// colours.
inline constexpr const char* kSourcePolygonProperty = "source_polygon";
inline constexpr const char* kColourProperty = "colour";

// How import() assigns 3-cells to the faces it builds.
enum class VolumeMode {
  kAuto,  // each face-connected closed, consistently oriented shell of positive
          // signed volume bounds its own cell (on the back of its faces)
  kNone,  // every face is a sheet face without volumes
};

struct ImportOptions {
  // Positions closer than this (max-norm distance) weld into one vertex. 0 (the
  // default) welds only positions whose coordinates are equal. With a tolerance the
  // first position of a cluster is kept and welding is greedy in input order.
  double weld_tolerance = 0;
  // Merge edge-adjacent coplanar triangles (exactly coplanar, same orientation) into
  // polygon faces, possibly with holes.
  bool merge_coplanar = false;
  // Flip faces so that each face-connected manifold patch is consistently oriented
  // (and closed shells point outward).
  bool repair_orientation = false;
  VolumeMode volumes = VolumeMode::kAuto;
  std::string group_name = {};  // overrides the soup's name
};

// What import() did to the soup before building it.
struct ImportReport {
  std::size_t input_positions = 0;
  std::size_t input_polygons = 0;
  std::size_t welded_vertices = 0;     // distinct positions after welding
  std::size_t unused_vertices = 0;     // positions no polygon, wire or point names (dropped)
  std::size_t degenerate_dropped = 0;  // polygons collapsed by welding (< 3 distinct corners)
  std::vector<std::size_t> degenerate_polygons;  // their indices in the soup (first 100)
  std::size_t merged_faces = 0;   // faces after merge_coplanar (== polygons without it)
  std::size_t flipped_faces = 0;  // faces turned by repair_orientation
  std::size_t closed_shells = 0;  // cells made by VolumeMode::kAuto
};

// Size limits of a read (docs/io.md, "Limits"). A file, or a stream without an end
// such as /dev/zero, is read up to max_bytes and refused past it; a 3MF archive
// whose entries declare more than max_3mf_bytes unpacked is refused before anything
// is unpacked. 0 means no limit.
inline constexpr std::uint64_t kDefaultMaxBytes = 1ull << 30;       // 1 GiB
inline constexpr std::uint64_t kDefaultMax3mfBytes = 256ull << 20;  // 256 MiB

struct ReadOptions {
  ImportOptions import;
  // The format, when the path does not say it: required for "-" (standard input),
  // and it overrides the extension otherwise.
  std::optional<Format> format = {};
  std::uint64_t max_bytes = kDefaultMaxBytes;
  std::uint64_t max_3mf_bytes = kDefaultMax3mfBytes;
};

// Sets one import option by name, as the command line and scripts give them:
// weld_tolerance=<number>, merge_coplanar=true|false, repair_orientation=true|false,
// volumes=auto|none, group_name=<text>. An error names the key or the bad value.
Status set_option(ImportOptions& options, std::string_view key, std::string_view value);
// The same, and the limits: max_bytes=N and max_3mf_bytes=N (a count of bytes, with
// an optional K, M or G suffix for KiB, MiB, GiB; 0 for no limit).
Status set_option(ReadOptions& options, std::string_view key, std::string_view value);

struct ReadResult {
  GroupId group;  // the first group read (formats other than JSON make one)
  ImportReport report;
  // JSON: the attachments the file keeps beside its model (topo/attachment.h),
  // byte for byte; other formats have none.
  std::vector<Attachment> attachments;
};

// Parses the bytes of a mesh format (not kJson) into a soup.
Result<PolygonSoup> parse_mesh(std::span<const std::uint8_t> bytes, Format format,
                               std::uint64_t max_3mf_bytes = kDefaultMax3mfBytes);
// Welds the soup and builds it into a new group of m. On error m is unchanged.
Result<ReadResult> import_soup(Model& m, const PolygonSoup& soup, const ImportOptions& options);

// Reads the bytes of any format into m (JSON: every group of the file is added).
Result<ReadResult> read_model(Model& m, std::span<const std::uint8_t> bytes, Format format,
                              const ReadOptions& options = {});
// Reads a file; the format comes from the extension, the group name (for mesh
// formats) from the file's stem unless options name one (bytes of the stem that are
// not UTF-8 become U+FFFD, so that every format can write the name).
Result<ReadResult> read_file(Model& m, const std::string& path, const ReadOptions& options = {});

struct WriteOptions {
  // The format, when the path does not say it: required for "-" (standard output),
  // and it overrides the extension otherwise.
  std::optional<Format> format = {};
  bool stl_binary = true;  // false: ASCII STL
  // OBJ and OFF keep polygons without holes as polygons; with `triangulate` every
  // face is written as triangles (faces with holes always are).
  bool triangulate = false;
  // 3MF: the color of each face (by FaceId value; r, g, b, alpha in [0, 1]), written
  // as the core specification's <basematerials>, one material per distinct color, and
  // each triangle's pid and p1. Faces without a color (or beyond the vector) take
  // OpenSCAD's default face color, #F9D72C. Empty: no materials are written. Other
  // formats ignore it.
  std::vector<std::optional<std::array<double, 4>>> face_colors = {};
  // JSON: attachments kept beside the model (topo/attachment.h; e.g. the exact
  // form of a Boolean result, boolean/exact.h), read back in ReadResult. The mesh
  // formats have no place for them: they round on the way out.
  std::vector<Attachment> attachments = {};
};

// The bytes of m in a format. Mesh formats triangulate faces as needed and write
// every group into one mesh (3MF: one object per group); OBJ also writes wire
// edges (`l`) and isolated vertices (`p`).
Result<std::string> write_model(const Model& m, Format format, const WriteOptions& options = {});
// Writes a file ("-": standard output, flushed); an error when any byte could not be
// written (a full disk, /dev/full) names the path.
Status write_file(const Model& m, const std::string& path, const WriteOptions& options = {});

// The format named "stl", "obj", "off", "3mf" or "json" (case-insensitive).
Result<Format> format_from_name(std::string_view name);

// What writing m in `format` leaves out, one sentence per kind of entity, with
// counts ("3 wire edges and 1 isolated point: STL holds only triangles"); empty
// when the format keeps everything its reader rebuilds.
std::vector<std::string> format_losses(const Model& m, Format format);

// Reads a whole file into memory, at most max_bytes of it (0: no limit); "-" reads
// standard input. Errors name the path and what was wrong (missing, a directory,
// larger than the limit).
Result<std::vector<std::uint8_t>> read_bytes(const std::string& path,
                                             std::uint64_t max_bytes = kDefaultMaxBytes);

}  // namespace cellforge::io
