// Format dispatch, files, and the read/write entry points of mesh_io.h.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "cellforge/topo/validate.h"
#include "io/formats.h"

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

Result<std::vector<std::uint8_t>> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{ErrorCode::kIo, "cannot open " + path};
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
  if (in.bad()) return Error{ErrorCode::kIo, "cannot read " + path};
  return bytes;
}

namespace {

std::string_view as_text(std::span<const std::uint8_t> bytes) {
  return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
}

}  // namespace

Result<PolygonSoup> parse_mesh(std::span<const std::uint8_t> bytes, Format format) {
  switch (format) {
    case Format::kStl:
      return parse_stl(bytes);
    case Format::kObj:
      return parse_obj(as_text(bytes));
    case Format::kOff:
      return parse_off(as_text(bytes));
    case Format::k3mf: {
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
  auto soup = parse_mesh(bytes, format);
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

Result<ReadResult> read_file(Model& m, const std::string& path, const ReadOptions& options) {
  auto format = format_from_path(path);
  if (!format) return format.error();
  auto bytes = read_bytes(path);
  if (!bytes) return bytes.error();
  ReadOptions named = options;
  if (named.import.group_name.empty())
    named.import.group_name = std::filesystem::path(path).stem().string();
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
      return write_3mf(m);
    case Format::kJson:
      // The reader validates what it restores: an invalid model would be written
      // but never read back, so it is refused here with the reader's reasons.
      if (auto violations = validate(m); !violations.empty())
        return Error{ErrorCode::kInvalidInput,
                     "json: the model is invalid, so the file could not be read back: " +
                         to_string(violations)};
      return write_json(m);
  }
  return Error{ErrorCode::kUnsupported, "unknown format"};
}

Status write_file(const Model& m, const std::string& path, const WriteOptions& options) {
  auto format = format_from_path(path);
  if (!format) return format.error();
  auto bytes = write_model(m, *format, options);
  if (!bytes) return bytes.error();
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) return Error{ErrorCode::kIo, "cannot create " + path};
  out.write(bytes->data(), static_cast<std::streamsize>(bytes->size()));
  out.close();
  if (!out) return Error{ErrorCode::kIo, "cannot write " + path};
  return Status::Ok();
}

}  // namespace cellforge::io
