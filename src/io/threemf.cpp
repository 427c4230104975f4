// 3MF through Debian's lib3mf (1.8, its C interface). Reading takes the build
// items that are mesh objects, with their transforms; each becomes one soup (and,
// through read_model, one group). Writing makes one mesh object and build item per
// group. 3MF stores single-precision floats, so coordinates round to float.
#include <cmath>
#include <cstring>

#include "io/formats.h"
#include "io/text.h"

#ifdef CELLFORGE_HAVE_LIB3MF
#include <Model/COM/NMR_DLLInterfaces.h>
#endif

namespace cellforge::io {

bool has_3mf() {
#ifdef CELLFORGE_HAVE_LIB3MF
  return true;
#else
  return false;
#endif
}

#ifndef CELLFORGE_HAVE_LIB3MF

Result<std::vector<PolygonSoup>> parse_3mf(std::span<const std::uint8_t>) {
  return Error{ErrorCode::kUnsupported, "3mf: this build has no lib3mf"};
}
Result<std::string> write_3mf(const Model&) {
  return Error{ErrorCode::kUnsupported, "3mf: this build has no lib3mf"};
}

#else

namespace {

using namespace NMR;

// Owns one lib3mf instance.
class Handle {
 public:
  Handle() = default;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() {
    if (p_) lib3mf_release(p_);
  }
  PLib3MFBase** out() { return &p_; }
  PLib3MFBase* get() const { return p_; }

 private:
  PLib3MFBase* p_ = nullptr;
};

Error lib_error(PLib3MFBase* object, const std::string& what) {
  DWORD code = 0;
  LPCSTR message = nullptr;
  std::string text;
  if (object && lib3mf_getlasterror(object, &code, &message) == LIB3MF_OK && message)
    text = message;
  return Error{ErrorCode::kParse, "3mf: " + what + (text.empty() ? "" : ": " + text) +
                                      " (lib3mf error " + std::to_string(code) + ")"};
}

Result<PolygonSoup> read_mesh(PLib3MFBase* object, const MODELTRANSFORM* transform,
                              std::size_t item) {
  DWORD nv = 0, nt = 0;
  if (lib3mf_meshobject_getvertexcount(object, &nv) != LIB3MF_OK ||
      lib3mf_meshobject_gettrianglecount(object, &nt) != LIB3MF_OK)
    return lib_error(object, "cannot read mesh of build item " + std::to_string(item));
  // The counts come from meshes lib3mf has already built in memory.
  std::vector<MODELMESHVERTEX> vertices(nv);
  std::vector<MODELMESHTRIANGLE> triangles(nt);
  DWORD got = 0;
  if ((nv && lib3mf_meshobject_getvertices(object, vertices.data(), nv, &got) != LIB3MF_OK) ||
      (nt && lib3mf_meshobject_gettriangleindices(object, triangles.data(), nt, &got) != LIB3MF_OK))
    return lib_error(object, "cannot read mesh of build item " + std::to_string(item));
  PolygonSoup soup;
  ULONG needed = 0;
  if (lib3mf_object_getnameutf8(object, nullptr, 0, &needed) == LIB3MF_OK && needed > 1 &&
      needed < 4096) {
    std::string name(needed, '\0');
    if (lib3mf_object_getnameutf8(object, name.data(), needed, &needed) == LIB3MF_OK) {
      name.resize(std::strlen(name.c_str()));
      soup.name = name;
    }
  }
  soup.positions.reserve(nv);
  for (DWORD i = 0; i < nv; ++i) {
    const float* p = vertices[i].m_fPosition;
    Vec3 v{p[0], p[1], p[2]};
    if (transform) {
      const auto& f = transform->m_fFields;
      v = {f[0][0] * v.x + f[0][1] * v.y + f[0][2] * v.z + f[0][3],
           f[1][0] * v.x + f[1][1] * v.y + f[1][2] * v.z + f[1][3],
           f[2][0] * v.x + f[2][1] * v.y + f[2][2] * v.z + f[2][3]};
    }
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
      return Error{ErrorCode::kParse, "3mf: build item " + std::to_string(item) + " vertex " +
                                          std::to_string(i) + " has a non-finite coordinate"};
    soup.positions.push_back(v);
  }
  soup.polygons.reserve(nt);
  for (DWORD t = 0; t < nt; ++t) {
    const DWORD* ix = triangles[t].m_nIndices;
    for (int k = 0; k < 3; ++k) {
      if (ix[k] >= nv)
        return Error{ErrorCode::kParse, "3mf: build item " + std::to_string(item) + " triangle " +
                                            std::to_string(t) + " names vertex " +
                                            std::to_string(ix[k]) + " of " + std::to_string(nv)};
    }
    soup.polygons.push_back({ix[0], ix[1], ix[2]});
  }
  return soup;
}

}  // namespace

Result<std::vector<PolygonSoup>> parse_3mf(std::span<const std::uint8_t> bytes) {
  if (bytes.empty()) return byte_error("3mf", 0, "empty file");
  if (bytes.size() < 4 || std::memcmp(bytes.data(), "PK\x03\x04", 4) != 0)
    return byte_error("3mf", 0, "not a ZIP archive (a 3MF file is a ZIP package; it starts 'PK')");
  Handle model, reader, items;
  if (lib3mf_createmodel(model.out()) != LIB3MF_OK)
    return Error{ErrorCode::kIo, "3mf: cannot create a lib3mf model"};
  if (lib3mf_model_queryreader(model.get(), "3mf", reader.out()) != LIB3MF_OK)
    return lib_error(model.get(), "no 3mf reader");
  std::vector<BYTE> copy(bytes.begin(), bytes.end());
  if (lib3mf_reader_readfrombuffer(reader.get(), copy.data(), copy.size()) != LIB3MF_OK)
    return lib_error(reader.get(), "cannot read the package");
  if (lib3mf_model_getbuilditems(model.get(), items.out()) != LIB3MF_OK)
    return lib_error(model.get(), "no build items");
  std::vector<PolygonSoup> soups;
  BOOL more = false;
  for (std::size_t item = 0;
       lib3mf_builditemiterator_movenext(items.get(), &more) == LIB3MF_OK && more; ++item) {
    Handle build_item, object;
    if (lib3mf_builditemiterator_getcurrent(items.get(), build_item.out()) != LIB3MF_OK ||
        lib3mf_builditem_getobjectresource(build_item.get(), object.out()) != LIB3MF_OK)
      return lib_error(items.get(), "cannot read build item " + std::to_string(item));
    BOOL is_mesh = false, has_transform = false;
    if (lib3mf_object_ismeshobject(object.get(), &is_mesh) != LIB3MF_OK || !is_mesh) continue;
    MODELTRANSFORM transform;
    if (lib3mf_builditem_hasobjecttransform(build_item.get(), &has_transform) == LIB3MF_OK &&
        has_transform &&
        lib3mf_builditem_getobjecttransform(build_item.get(), &transform) != LIB3MF_OK)
      return lib_error(build_item.get(),
                       "cannot read the transform of build item " + std::to_string(item));
    auto soup = read_mesh(object.get(), has_transform ? &transform : nullptr, item);
    if (!soup) return soup.error();
    soups.push_back(std::move(*soup));
  }
  if (soups.empty()) return Error{ErrorCode::kParse, "3mf: the package builds no mesh object"};
  return soups;
}

Result<std::string> write_3mf(const Model& m) {
  Handle model, writer;
  if (lib3mf_createmodel(model.out()) != LIB3MF_OK)
    return Error{ErrorCode::kIo, "3mf: cannot create a lib3mf model"};
  const TriangleMesh mesh = triangle_mesh(m);
  for (GroupId g : m.groups()) {
    std::vector<MODELMESHVERTEX> vertices;
    std::vector<MODELMESHTRIANGLE> triangles;
    std::vector<DWORD> local(mesh.positions.size(), kInvalidIndex);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      if (m.group_of(mesh.face_of[t]) != g) continue;
      MODELMESHTRIANGLE tri;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t i = mesh.triangles[t][k];
        if (local[i] == kInvalidIndex) {
          local[i] = static_cast<DWORD>(vertices.size());
          const Vec3 p = mesh.positions[i];
          vertices.push_back(
              {{static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)}});
        }
        tri.m_nIndices[k] = local[i];
      }
      triangles.push_back(tri);
    }
    if (triangles.empty()) continue;
    Handle object, item;
    if (lib3mf_model_addmeshobject(model.get(), object.out()) != LIB3MF_OK ||
        lib3mf_meshobject_setgeometry(object.get(), vertices.data(),
                                      static_cast<DWORD>(vertices.size()), triangles.data(),
                                      static_cast<DWORD>(triangles.size())) != LIB3MF_OK)
      return lib_error(model.get(), "cannot add the mesh of group " + g.str());
    if (!m.name(g).empty()) lib3mf_object_setnameutf8(object.get(), m.name(g).c_str());
    if (lib3mf_model_addbuilditem(model.get(), object.get(), nullptr, item.out()) != LIB3MF_OK)
      return lib_error(model.get(), "cannot add a build item");
  }
  if (lib3mf_model_querywriter(model.get(), "3mf", writer.out()) != LIB3MF_OK)
    return lib_error(model.get(), "no 3mf writer");
  ULONG64 size = 0;
  if (lib3mf_writer_getstreamsize(writer.get(), &size) != LIB3MF_OK)
    return lib_error(writer.get(), "cannot size the package");
  std::string out(size, '\0');
  if (lib3mf_writer_writetobuffer(writer.get(), reinterpret_cast<BYTE*>(out.data()), size) !=
      LIB3MF_OK)
    return lib_error(writer.get(), "cannot write the package");
  return out;
}

#endif

}  // namespace cellforge::io
