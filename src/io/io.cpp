// Format dispatch, files, and the read/write entry points of mesh_io.h.
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "cellforge/topo/validate.h"
#include "io/formats.h"
#include "io/text.h"

namespace cellforge::io {

std::string_view format_name(Format f) {
  switch (f) {
    case Format::kStl:
      return "stl";
    case Format::kObj:
      return "obj";
    case Format::kOff:
      return "off";
    case Format::k3mf:
      return "3mf";
    case Format::kJson:
      return "json";
  }
  return "?";
}

Result<Format> format_from_path(std::string_view path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  std::string lower;
  for (char c : ext) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (Format f : {Format::kStl, Format::kObj, Format::kOff, Format::k3mf, Format::kJson})
    if (lower == "." + std::string(format_name(f))) return f;
  return Error{ErrorCode::kUnsupported, "unknown file extension '" + ext + "' of " +
                                            std::string(path) +
                                            " (known: .stl .obj .off .3mf .json)"};
}

Result<std::vector<std::uint8_t>> read_bytes(const std::string& path, std::uint64_t max_bytes) {
  const bool standard_input = path == "-";
  const std::string shown = standard_input ? std::string("standard input") : path;
  std::FILE* f = standard_input ? stdin : std::fopen(path.c_str(), "rb");
  if (f == nullptr)
    return Error{ErrorCode::kIo, "cannot open " + path + ": " + std::strerror(errno)};
  struct stat st {};
  if (fstat(fileno(f), &st) == 0 && S_ISDIR(st.st_mode)) {
    if (!standard_input) std::fclose(f);
    return Error{ErrorCode::kIo, shown + ": is a directory, not a file"};
  }
  const auto too_large_error = [&] {
    return Error{ErrorCode::kIo, shown + ": larger than the read limit of " +
                                     std::to_string(max_bytes) +
                                     " bytes (the option max_bytes=N raises it, 0 lifts it)"};
  };
  // A regular file's size is known: refused at once past the limit, else read with
  // one allocation.
  if (S_ISREG(st.st_mode) && max_bytes != 0 && static_cast<std::uint64_t>(st.st_size) > max_bytes) {
    if (!standard_input) std::fclose(f);
    return too_large_error();
  }
  std::vector<std::uint8_t> bytes;
  if (S_ISREG(st.st_mode) && st.st_size > 0 &&
      (max_bytes == 0 || static_cast<std::uint64_t>(st.st_size) <= max_bytes))
    bytes.reserve(static_cast<std::size_t>(st.st_size));
  std::uint8_t chunk[1 << 16];
  bool too_large = false;
  while (true) {
    const std::size_t n = std::fread(chunk, 1, sizeof chunk, f);
    if (max_bytes != 0 && bytes.size() + n > max_bytes) {
      too_large = true;
      break;
    }
    bytes.insert(bytes.end(), chunk, chunk + n);
    if (n < sizeof chunk) break;
  }
  const bool failed = std::ferror(f) != 0;
  const int error = errno;
  if (!standard_input) std::fclose(f);
  if (too_large) return too_large_error();
  if (failed) return Error{ErrorCode::kIo, "cannot read " + shown + ": " + std::strerror(error)};
  return bytes;
}

namespace {

std::string_view as_text(std::span<const std::uint8_t> bytes) {
  return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
}

}  // namespace

Result<PolygonSoup> parse_mesh(std::span<const std::uint8_t> bytes, Format format,
                               std::uint64_t max_3mf_bytes) {
  switch (format) {
    case Format::kStl:
      return parse_stl(bytes);
    case Format::kObj:
      return parse_obj(as_text(bytes));
    case Format::kOff:
      return parse_off(as_text(bytes));
    case Format::k3mf: {
      if (Status s = check_zip_size("3mf", bytes, max_3mf_bytes); !s) return s.error();
      auto parts = parse_3mf(bytes);
      if (!parts) return parts.error();
      // One soup: the objects side by side (read_model keeps them apart).
      PolygonSoup all;
      for (const PolygonSoup& s : *parts) {
        const auto base = static_cast<std::uint32_t>(all.positions.size());
        all.positions.insert(all.positions.end(), s.positions.begin(), s.positions.end());
        for (auto p : s.polygons) {
          for (auto& i : p) i += base;
          all.polygons.push_back(std::move(p));
        }
        if (all.name.empty()) all.name = s.name;
      }
      return all;
    }
    case Format::kJson:
      break;
  }
  return Error{ErrorCode::kUnsupported, "json is not a mesh format; use read_model"};
}

Result<ReadResult> read_model(Model& m, std::span<const std::uint8_t> bytes, Format format,
                              const ReadOptions& options) {
  if (format == Format::kJson) return read_json(m, as_text(bytes));
  if (format == Format::k3mf) {
    // Each object of the package becomes its own group.
    if (Status s = check_zip_size("3mf", bytes, options.max_3mf_bytes); !s) return s.error();
    auto parts = parse_3mf(bytes);
    if (!parts) return parts.error();
    Model staged = m;  // all or nothing
    ReadResult first;
    for (std::size_t i = 0; i < parts->size(); ++i) {
      auto r = import_soup(staged, (*parts)[i], options.import);
      if (!r)
        return Error{r.error().code, "3mf object " + std::to_string(i) + ": " + r.error().message};
      if (i == 0) first = *r;
    }
    m = std::move(staged);
    return first;
  }
  auto soup = parse_mesh(bytes, format, options.max_3mf_bytes);
  if (!soup) return soup.error();
  return import_soup(m, *soup, options.import);
}

Status set_option(ImportOptions& options, std::string_view key, std::string_view value) {
  const auto flag = [&](bool& out) -> Status {
    if (value == "true" || value == "1" || value == "yes") {
      out = true;
    } else if (value == "false" || value == "0" || value == "no") {
      out = false;
    } else {
      return Error{ErrorCode::kInvalidInput,
                   std::string(key) + " takes true or false, not '" + std::string(value) + "'"};
    }
    return Status::Ok();
  };
  if (key == "weld_tolerance") {
    double t = 0;
    const std::string v(value);
    char* end = nullptr;
    t = std::strtod(v.c_str(), &end);
    if (v.empty() || *end != '\0' || !std::isfinite(t) || t < 0)
      return Error{ErrorCode::kInvalidInput,
                   "weld_tolerance takes a finite number >= 0, not '" + v + "'"};
    options.weld_tolerance = t;
    return Status::Ok();
  }
  if (key == "merge_coplanar") return flag(options.merge_coplanar);
  if (key == "repair_orientation") return flag(options.repair_orientation);
  if (key == "volumes") {
    if (value == "auto") {
      options.volumes = VolumeMode::kAuto;
    } else if (value == "none") {
      options.volumes = VolumeMode::kNone;
    } else {
      return Error{ErrorCode::kInvalidInput,
                   "volumes takes auto or none, not '" + std::string(value) + "'"};
    }
    return Status::Ok();
  }
  if (key == "group_name") {
    options.group_name = std::string(value);
    return Status::Ok();
  }
  return Error{ErrorCode::kInvalidInput,
               "unknown import option '" + std::string(key) +
                   "' (weld_tolerance, merge_coplanar, repair_orientation, volumes, group_name)"};
}

Status set_option(ReadOptions& options, std::string_view key, std::string_view value) {
  if (key != "max_bytes" && key != "max_3mf_bytes") return set_option(options.import, key, value);
  std::uint64_t n = 0, unit = 1;
  std::string_view digits = value;
  if (!digits.empty()) {
    switch (digits.back()) {
      case 'K':
      case 'k':
        unit = 1ull << 10;
        break;
      case 'M':
      case 'm':
        unit = 1ull << 20;
        break;
      case 'G':
      case 'g':
        unit = 1ull << 30;
        break;
      default:
        break;
    }
    if (unit != 1) digits.remove_suffix(1);
  }
  const auto r = std::from_chars(digits.data(), digits.data() + digits.size(), n);
  if (digits.empty() || r.ec != std::errc() || r.ptr != digits.data() + digits.size() ||
      n > UINT64_MAX / unit)
    return Error{ErrorCode::kInvalidInput,
                 std::string(key) + " takes a count of bytes (optionally with K, M or G), not '" +
                     std::string(value) + "'"};
  (key == "max_bytes" ? options.max_bytes : options.max_3mf_bytes) = n * unit;
  return Status::Ok();
}

Result<Format> format_from_name(std::string_view name) {
  std::string lower;
  for (char c : name) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (Format f : {Format::kStl, Format::kObj, Format::kOff, Format::k3mf, Format::kJson})
    if (lower == format_name(f)) return f;
  return Error{ErrorCode::kInvalidInput,
               "unknown format '" + std::string(name) + "' (stl, obj, off, 3mf, json)"};
}

namespace {

Result<Format> format_of(const std::string& path, const std::optional<Format>& given,
                         const char* direction) {
  if (given) return *given;
  if (path == "-")
    return Error{ErrorCode::kInvalidInput,
                 std::string(direction) + " needs a format named (stl, obj, off, 3mf, json)"};
  return format_from_path(path);
}

}  // namespace

std::vector<std::string> format_losses(const Model& m, Format format) {
  std::vector<std::string> out;
  if (format == Format::kJson) {
    const std::vector<std::string> unstored = unstored_properties(m);
    if (!unstored.empty()) {
      std::string names;
      for (const std::string& n : unstored) names += (names.empty() ? "" : ", ") + n;
      out.push_back(names + " not written: JSON keeps property values of the types of "
                    "PropertyType only");
    }
    return out;
  }
  std::size_t wires = 0, points = 0, groups = 0, attributes = 0;
  for (EdgeId e : m.edges()) wires += m.is_wire(e);
  for (VertexId v : m.vertices())
    points += !m.first_end(v).edge.is_valid() && !m.point_loop(v).is_valid();
  for (GroupId g : m.groups()) {
    ++groups;
    attributes += m.attributes(g).size();
  }
  const std::string name(format_name(format));
  const auto plural = [](std::size_t n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
  };
  if (format != Format::kObj && (wires || points)) {
    std::string what;
    if (wires) what = plural(wires, "wire edge", "wire edges");
    if (points)
      what += (what.empty() ? "" : " and ") + plural(points, "isolated point", "isolated points");
    out.push_back(what + " not written: " + name + " holds faces only (OBJ and JSON keep them)");
  }
  if ((format == Format::kStl || format == Format::kOff) && groups > 1)
    out.push_back(plural(groups, "group", "groups") + " written as one mesh: " + name +
                  " has no groups (3MF, OBJ and JSON keep them)");
  if (attributes)
    out.push_back(plural(attributes, "group attribute", "group attributes") +
                  " (kind, parameters) not written: only JSON keeps them");
  return out;
}

Result<ReadResult> read_file(Model& m, const std::string& path, const ReadOptions& options) {
  auto format = format_of(path, options.format, "reading standard input");
  if (!format) return format.error();
  auto bytes = read_bytes(path, options.max_bytes);
  if (!bytes) return bytes.error();
  ReadOptions named = options;
  if (named.import.group_name.empty() && path != "-")
    named.import.group_name = valid_utf8(std::filesystem::path(path).stem().string());
  auto r = read_model(m, *bytes, *format, named);
  if (!r) return Error{r.error().code, path + ": " + r.error().message};
  return r;
}

Result<std::string> write_model(const Model& m, Format format, const WriteOptions& options) {
  switch (format) {
    case Format::kStl: {
      std::string name;
      for (GroupId g : m.groups()) {
        name = m.name(g);
        break;
      }
      return write_stl(triangle_mesh(m), options.stl_binary, name);
    }
    case Format::kObj:
      return write_obj(m, options);
    case Format::kOff:
      return write_off(m, options);
    case Format::k3mf:
      return write_3mf(m, options.face_colors);
    case Format::kJson:
      // The reader validates what it restores: an invalid model would be written
      // but never read back, so it is refused here with the reader's reasons.
      if (auto violations = validate(m); !violations.empty())
        return Error{ErrorCode::kInvalidInput,
                     "json: the model is invalid, so the file could not be read back: " +
                         to_string(violations)};
      return write_json(m, options.attachments);
  }
  return Error{ErrorCode::kUnsupported, "unknown format"};
}

Status write_file(const Model& m, const std::string& path, const WriteOptions& options) {
  auto format = format_of(path, options.format, "writing standard output");
  if (!format) return format.error();
  auto bytes = write_model(m, *format, options);
  if (!bytes) return bytes.error();
  if (path == "-") {
    if (std::fwrite(bytes->data(), 1, bytes->size(), stdout) != bytes->size() ||
        std::fflush(stdout) != 0)
      return Error{ErrorCode::kIo,
                   std::string("cannot write standard output: ") + std::strerror(errno)};
    return Status::Ok();
  }
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) return Error{ErrorCode::kIo, "cannot create " + path};
  out.write(bytes->data(), static_cast<std::streamsize>(bytes->size()));
  out.close();
  if (!out) return Error{ErrorCode::kIo, "cannot write " + path};
  return Status::Ok();
}

}  // namespace cellforge::io
