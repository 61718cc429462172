#include "millsim/graphics/ShapeMeshes.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "millsim/std/ColorNode.h"
#include "millsim/std/Cone.h"
#include "millsim/std/Coordinate.h"
#include "millsim/std/IndexedFaceSet.h"
#include "millsim/std/IndexedTriangleSet.h"
#include "millsim/std/Normal.h"
#include "millsim/std/TextureCoordinate.h"

namespace millsim {

namespace {

constexpr float kPi = 3.14159265358979323846f;

// What a composed geometry's faces are made of, in IndexedFaceSet's terms:
// an IndexedTriangleSet is faces of three with the same per-vertex rules.
struct FaceInput {
  std::vector<std::int32_t> coordIndex;  // −1 ends a face
  const std::vector<glm::vec3>* points = nullptr;
  const std::vector<glm::vec3>* normals = nullptr;
  const std::vector<std::int32_t>* normalIndex = nullptr;
  bool normalPerVertex = true;
  const std::vector<Color>* colours = nullptr;
  const std::vector<std::int32_t>* colorIndex = nullptr;
  bool colorPerVertex = true;
  const std::vector<glm::vec2>* texCoords = nullptr;
  const std::vector<std::int32_t>* texCoordIndex = nullptr;
  bool ccw = true;
  float creaseAngle = 0.f;
};

template <class T> const T* at(const std::vector<T>* v, std::int64_t i) {
  return v && i >= 0 && std::size_t(i) < v->size() ? &(*v)[std::size_t(i)] : nullptr;
}

// Index for corner p of face f: the explicit index array if it has entries,
// else the coordinate index (per vertex) or the face number (per face).
std::int64_t indexFor(const std::vector<std::int32_t>* explicitIndex, bool perVertex, const FaceInput& in, std::size_t p,
                      std::size_t f) {
  const bool has = explicitIndex && !explicitIndex->empty();
  if (perVertex) return has ? (p < explicitIndex->size() ? (*explicitIndex)[p] : -1) : in.coordIndex[p];
  return has ? (f < explicitIndex->size() ? (*explicitIndex)[f] : -1) : std::int64_t(f);
}

TriangleMesh build(const FaceInput& in) {
  TriangleMesh mesh;
  const std::vector<glm::vec3>& pts = *in.points;
  // Faces as [first, end) ranges of coordIndex, only those whose every index is valid.
  struct Face {
    std::size_t first, end;
    glm::vec3 normal;
  };
  std::vector<Face> faces;
  std::vector<std::size_t> faceNumber;  // a face's number counts skipped faces too (per-face data)
  std::size_t start = 0, number = 0;
  for (std::size_t i = 0; i <= in.coordIndex.size(); ++i) {
    if (i < in.coordIndex.size() && in.coordIndex[i] != -1) continue;
    bool valid = i - start >= 3;
    for (std::size_t j = start; valid && j < i; ++j) valid = at(&pts, in.coordIndex[j]) != nullptr;
    if (valid) {
      // Newell's normal: right for any planar polygon and sensible for a warped one.
      glm::vec3 n(0.f);
      for (std::size_t j = start; j < i; ++j) {
        const glm::vec3& a = pts[std::size_t(in.coordIndex[j])];
        const glm::vec3& b = pts[std::size_t(in.coordIndex[j + 1 < i ? j + 1 : start])];
        n += glm::vec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
      }
      const float len = glm::length(n);
      n = len > 0.f ? n / len : glm::vec3(0.f, 0.f, 1.f);
      faces.push_back({start, i, in.ccw ? n : -n});
      faceNumber.push_back(number);
    }
    if (i > start || i < in.coordIndex.size()) ++number;
    start = i + 1;
  }
  // Faces around each vertex, for smoothed normals.
  const bool computeNormals = !in.normals || in.normals->empty();
  const bool smooth = computeNormals && in.normalPerVertex && in.creaseAngle > 0.f;
  std::vector<std::vector<std::uint32_t>> around;
  if (smooth) {
    around.resize(pts.size());
    for (std::size_t f = 0; f < faces.size(); ++f)
      for (std::size_t j = faces[f].first; j < faces[f].end; ++j) around[std::size_t(in.coordIndex[j])].push_back(std::uint32_t(f));
  }
  const float cosCrease = std::cos(std::min(in.creaseAngle, kPi));
  // X3D's default texture mapping: s along the bounding box's longest side, t along the next, both scaled by the longest.
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const glm::vec3& p : pts) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::vec3 size = pts.empty() ? glm::vec3(1.f) : hi - lo;
  int sAxis = 0;
  for (int a = 1; a < 3; ++a)
    if (size[a] > size[sAxis]) sAxis = a;
  int tAxis = sAxis == 0 ? 1 : 0;
  for (int a = 0; a < 3; ++a)
    if (a != sAxis && size[a] > size[tAxis]) tAxis = a;
  const float scale = size[sAxis] > 0.f ? 1.f / size[sAxis] : 1.f;
  const bool hasColours = in.colours && !in.colours->empty();
  const bool hasTex = in.texCoords && !in.texCoords->empty();

  auto corner = [&](std::size_t f, std::size_t p) {
    const std::size_t v = std::size_t(in.coordIndex[p]);
    mesh.positions.push_back(pts[v]);
    glm::vec3 n = faces[f].normal;
    if (!computeNormals) {
      if (const glm::vec3* given = at(in.normals, indexFor(in.normalIndex, in.normalPerVertex, in, p, faceNumber[f]))) {
        const float len = glm::length(*given);
        if (len > 0.f && std::isfinite(len)) n = *given / len;
      }
    } else if (smooth) {
      glm::vec3 sum(0.f);
      for (std::uint32_t g : around[v])
        if (glm::dot(faces[g].normal, faces[f].normal) >= cosCrease - 1e-6f) sum += faces[g].normal;
      const float len = glm::length(sum);
      if (len > 0.f) n = sum / len;
    }
    mesh.normals.push_back(n);
    if (hasColours) {
      const Color* c = at(in.colours, indexFor(in.colorIndex, in.colorPerVertex, in, p, faceNumber[f]));
      mesh.colours.push_back(c ? c->rgb : glm::vec3(1.f));
    }
    if (hasTex) {
      const glm::vec2* t = at(in.texCoords, indexFor(in.texCoordIndex, true, in, p, faceNumber[f]));
      mesh.texCoords.push_back(t ? *t : glm::vec2(0.f));
    } else {
      mesh.texCoords.push_back(glm::vec2((pts[v][sAxis] - lo[sAxis]) * scale, (pts[v][tAxis] - lo[tAxis]) * scale));
    }
  };
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (std::size_t j = faces[f].first + 1; j + 1 < faces[f].end; ++j) {
      // A fan from the face's first corner, wound so that ccw FALSE faces still face their normal.
      corner(f, faces[f].first);
      corner(f, in.ccw ? j : j + 1);
      corner(f, in.ccw ? j + 1 : j);
    }
  mesh.computeBounds();
  return mesh;
}

// Fills the per-vertex data fields every composed geometry shares.
template <class G> void readComposed(const G& g, FaceInput& in) {
  static const std::vector<glm::vec3> none;
  const auto* coord = dynamic_cast<const Coordinate*>(g.coord.get().get());
  in.points = coord ? &coord->point.get() : &none;
  if (const auto* n = dynamic_cast<const Normal*>(g.normal.get().get())) in.normals = &n->vector.get();
  if (const auto* c = dynamic_cast<const ColorNode*>(g.color.get().get())) in.colours = &c->color.get();
  if (const auto* t = dynamic_cast<const TextureCoordinate*>(g.texCoord.get().get())) in.texCoords = &t->point.get();
  in.normalPerVertex = g.normalPerVertex.get();
  in.colorPerVertex = g.colorPerVertex.get();
  in.ccw = g.ccw.get();
}

void push(TriangleMesh& m, const glm::vec3& p, const glm::vec3& n, const glm::vec2& uv) {
  m.positions.push_back(p);
  m.normals.push_back(glm::normalize(n));
  m.texCoords.push_back(uv);
}

// Around +Y, counter-clockwise seen from above, starting at the back (−Z), as X3D wraps textures.
glm::vec3 around(float s) { return glm::vec3(-std::sin(2.f * kPi * s), 0.f, -std::cos(2.f * kPi * s)); }

// A disc at height y facing `up` (±1), textured as its shadow on the XZ plane.
void disc(TriangleMesh& m, float y, float up, float radius, int slices) {
  for (int i = 0; i < slices; ++i) {
    const glm::vec3 a = around(float(i) / float(slices)) * radius, b = around(float(i + 1) / float(slices)) * radius;
    const glm::vec3 c(0.f, y, 0.f), pa(a.x, y, a.z), pb(b.x, y, b.z);
    auto uv = [&](const glm::vec3& p) { return glm::vec2(0.5f + 0.5f * p.x / radius, 0.5f - 0.5f * up * p.z / radius); };
    push(m, c, {0.f, up, 0.f}, uv(c));
    push(m, up > 0 ? pa : pb, {0.f, up, 0.f}, uv(up > 0 ? pa : pb));
    push(m, up > 0 ? pb : pa, {0.f, up, 0.f}, uv(up > 0 ? pb : pa));
  }
}

}  // namespace

TriangleMesh meshOf(const IndexedFaceSet& faces) {
  FaceInput in;
  in.coordIndex = faces.coordIndex.get();
  readComposed(faces, in);
  in.normalIndex = &faces.normalIndex.get();
  in.colorIndex = &faces.colorIndex.get();
  in.texCoordIndex = &faces.texCoordIndex.get();
  in.creaseAngle = faces.creaseAngle.get();
  return build(in);
}

TriangleMesh meshOf(const IndexedTriangleSet& triangles) {
  FaceInput in;
  const auto& index = triangles.index.get();
  for (std::size_t i = 0; i + 2 < index.size(); i += 3) in.coordIndex.insert(in.coordIndex.end(), {index[i], index[i + 1], index[i + 2], -1});
  readComposed(triangles, in);
  // Without normals, per-vertex ones are smooth over the whole mesh (the node has no creaseAngle).
  in.creaseAngle = kPi;
  return build(in);
}

TriangleMesh meshOf(const Cone& cone) {
  TriangleMesh m;
  const float r = cone.bottomRadius.get(), h = cone.height.get();
  const int slices = 48;
  if (cone.side.get())
    for (int i = 0; i < slices; ++i) {
      const float s0 = float(i) / float(slices), s1 = float(i + 1) / float(slices), sm = 0.5f * (s0 + s1);
      const glm::vec3 a = around(s0), b = around(s1), mid = around(sm);
      // The side's normal leans up by the slope r/h.
      auto normal = [&](const glm::vec3& d) { return glm::vec3(d.x * h, r, d.z * h); };
      push(m, glm::vec3(0.f, 0.5f * h, 0.f), normal(mid), {sm, 1.f});
      push(m, a * r + glm::vec3(0.f, -0.5f * h, 0.f), normal(a), {s0, 0.f});
      push(m, b * r + glm::vec3(0.f, -0.5f * h, 0.f), normal(b), {s1, 0.f});
    }
  if (cone.bottom.get()) disc(m, -0.5f * h, -1.f, r, slices);
  m.computeBounds();
  return m;
}

TriangleMesh texturedSphere(int slices, int stacks) {
  TriangleMesh m;
  auto point = [&](float s, float t) {
    const float phi = kPi * t;  // 0 at the bottom
    return around(s) * std::sin(phi) + glm::vec3(0.f, -std::cos(phi), 0.f);
  };
  for (int j = 0; j < stacks; ++j)
    for (int i = 0; i < slices; ++i) {
      const float s0 = float(i) / float(slices), s1 = float(i + 1) / float(slices);
      const float t0 = float(j) / float(stacks), t1 = float(j + 1) / float(stacks);
      const glm::vec3 a = point(s0, t0), b = point(s1, t0), c = point(s1, t1), d = point(s0, t1);
      push(m, a, a, {s0, t0}), push(m, b, b, {s1, t0}), push(m, c, c, {s1, t1});
      push(m, a, a, {s0, t0}), push(m, c, c, {s1, t1}), push(m, d, d, {s0, t1});
    }
  m.computeBounds();
  return m;
}

TriangleMesh texturedCylinder(int slices) {
  TriangleMesh m;
  for (int i = 0; i < slices; ++i) {
    const float s0 = float(i) / float(slices), s1 = float(i + 1) / float(slices);
    const glm::vec3 a = around(s0), b = around(s1);
    const glm::vec3 lo(0.f, -0.5f, 0.f), hi(0.f, 0.5f, 0.f);
    push(m, a + lo, a, {s0, 0.f}), push(m, b + lo, b, {s1, 0.f}), push(m, b + hi, b, {s1, 1.f});
    push(m, a + lo, a, {s0, 0.f}), push(m, b + hi, b, {s1, 1.f}), push(m, a + hi, a, {s0, 1.f});
  }
  disc(m, 0.5f, 1.f, 1.f, slices);
  disc(m, -0.5f, -1.f, 1.f, slices);
  m.computeBounds();
  return m;
}

TriangleMesh texturedBox() {
  TriangleMesh m;
  // Each face shows the whole image upright, seen from outside (X3D 13.3.1).
  struct FaceAxes {
    glm::vec3 normal, s, t;
  };
  const FaceAxes faces[] = {{{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},
                            {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}}, {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
                            {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}}, {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}};
  for (const FaceAxes& f : faces) {
    auto p = [&](float s, float t) { return 0.5f * f.normal + (s - 0.5f) * f.s + (t - 0.5f) * f.t; };
    push(m, p(0, 0), f.normal, {0, 0}), push(m, p(1, 0), f.normal, {1, 0}), push(m, p(1, 1), f.normal, {1, 1});
    push(m, p(0, 0), f.normal, {0, 0}), push(m, p(1, 1), f.normal, {1, 1}), push(m, p(0, 1), f.normal, {0, 1});
  }
  m.computeBounds();
  return m;
}

}  // namespace millsim
