// Canonical and raw dumps. The canonical dump names every entity by geometry
// instead of by id: a vertex by its exact position (hex floats), a face by its
// loops' position cycles rotated to their least rotation, a volume by the least
// face side bounding it, an edge by its sorted end positions with its radial
// cycle (face, direction) rotated to its least element. Sorted lines make it
// independent of ids, free lists and creation order.
#include "cellforge/topo/dump.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>

namespace cellforge::inline topo {

namespace {

std::string hex(Vec3 p) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "(%a %a %a)", p.x, p.y, p.z);
  return buf;
}

template <class T>
void rotate_to_least(std::vector<T>& v) {
  if (v.empty()) return;
  std::vector<T> best = v;
  for (std::size_t i = 1; i < v.size(); ++i) {
    std::vector<T> r(v.begin() + static_cast<std::ptrdiff_t>(i), v.end());
    r.insert(r.end(), v.begin(), v.begin() + static_cast<std::ptrdiff_t>(i));
    if (r < best) best = std::move(r);
  }
  v = std::move(best);
}

std::string join(const std::vector<std::string>& parts, const char* sep) {
  std::string s;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (i) s += sep;
    s += parts[i];
  }
  return s;
}

}  // namespace

std::string canonical_dump(const Model& m) {
  std::vector<std::string> lines;
  auto vkey = [&](VertexId v) { return hex(m.position(v)); };

  // Faces by geometry first (volumes are named after faces).
  std::map<FaceId, std::string> face_geo;
  for (FaceId f : m.faces()) {
    std::vector<std::string> inner;
    std::string outer;
    for (LoopId l : m.loops_of(f)) {
      std::vector<std::string> cycle;
      for (VertexId v : m.loop_vertices(l)) cycle.push_back(vkey(v));
      if (m.is_point_loop(l)) cycle[0] = "point" + cycle[0];
      rotate_to_least(cycle);
      (l == m.outer_loop(f) ? outer : inner.emplace_back()) = "[" + join(cycle, " ") + "]";
    }
    std::sort(inner.begin(), inner.end());
    face_geo[f] =
        "outer=" + outer + " inner={" + join(inner, ",") + "} group=" + m.name(m.group_of(f));
  }
  std::map<VolumeId, std::string> volume_key;
  for (FaceId f : m.faces()) {
    for (bool front : {true, false}) {
      const VolumeId c = front ? m.front_volume(f) : m.back_volume(f);
      if (!c.is_valid()) continue;
      std::string k = (front ? "front:" : "back:") + face_geo[f];
      auto [it, fresh] = volume_key.try_emplace(c, k);
      if (!fresh && k < it->second) it->second = k;
    }
  }
  auto volname = [&](VolumeId c) { return c.is_valid() ? "<" + volume_key[c] + ">" : "-"; };
  std::map<FaceId, std::string> face_key;
  for (FaceId f : m.faces()) {
    std::string k =
        face_geo[f] + " front=" + volname(m.front_volume(f)) + " back=" + volname(m.back_volume(f));
    const std::uint32_t s = m.surface_of(f);
    if (s != kInvalidIndex) {
      const Surface& sf = m.surface(s);
      std::ostringstream os;
      os << " surface=" << sf.kind << hex(sf.center) << hex(sf.axis) << sf.radius << ','
         << sf.radius2 << ',' << sf.height << ',' << sf.segments;
      k += os.str();
    }
    face_key[f] = k;
    lines.push_back("F " + k);
  }
  for (VertexId v : m.vertices()) {
    lines.push_back("V " + vkey(v) + " group=" + m.name(m.group_of(v)) +
                    " degree=" + std::to_string(m.degree(v)));
  }
  for (EdgeId e : m.edges()) {
    std::string a = vkey(m.start_of(e)), b = vkey(m.end_of(e));
    const bool flip = b < a;
    std::vector<std::string> cycle;
    for (EdgeUseId u : m.radial(e))
      cycle.push_back((m.is_reversed(u) != flip ? "-" : "+") + face_key[m.face_of(u)]);
    if (flip) {
      std::swap(a, b);
      std::reverse(cycle.begin(), cycle.end());
    }
    rotate_to_least(cycle);
    lines.push_back("E " + a + " " + b + " radial={" + join(cycle, " | ") + "}");
  }
  for (GroupId g : m.groups()) {
    std::string s = "G " + m.name(g);
    for (const Attribute& at : m.attributes(g)) s += " " + at.key + "=" + at.value;
    lines.push_back(s);
  }
  for (VolumeId c : m.volumes()) lines.push_back("C " + volname(c));
  std::sort(lines.begin(), lines.end());
  return join(lines, "\n") + "\n";
}

std::string raw_dump(const Model& m) {
  std::ostringstream os;
  for (VertexId v : m.vertices()) {
    os << v << ' ' << m.position(v) << ' ' << m.group_of(v) << " edges:";
    for (EdgeEnd end : m.ends_around(v)) os << ' ' << end.edge << (end.end ? "-" : "+");
    if (m.point_loop(v).is_valid()) os << " point-loop " << m.point_loop(v);
    os << '\n';
  }
  for (EdgeId e : m.edges()) {
    os << e << ' ' << m.start_of(e) << "->" << m.end_of(e) << " radial:";
    for (EdgeUseId u : m.radial(e))
      os << ' ' << u << (m.is_reversed(u) ? "-" : "+") << m.face_of(u);
    os << '\n';
  }
  for (FaceId f : m.faces()) {
    os << f << " front " << m.front_volume(f) << " back " << m.back_volume(f) << " group "
       << m.group_of(f);
    for (LoopId l : m.loops_of(f)) {
      os << " | " << l << ':';
      for (VertexId v : m.loop_vertices(l)) os << ' ' << v;
    }
    os << '\n';
  }
  return os.str();
}

}  // namespace cellforge::inline topo
