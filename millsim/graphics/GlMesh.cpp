#include "millsim/graphics/GlMesh.h"

#include <cmath>
#include <cstddef>
#include <numbers>
#include <utility>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

namespace millsim {

GlMesh::GlMesh(bool vertexColours) {
  glGenVertexArrays(1, &vao_);
  glGenBuffers(1, &vbo_);
  glGenBuffers(1, &ebo_);
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);  // recorded in the VAO
  const auto stride = GLsizei(sizeof(Vertex));
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(Vertex, position)));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(Vertex, normal)));
  if (vertexColours) glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(Vertex, colour)));
  glBindVertexArray(0);
}

GlMesh::~GlMesh() { release(); }

GlMesh::GlMesh(GlMesh&& o) noexcept
    : vao_(std::exchange(o.vao_, 0)), vbo_(std::exchange(o.vbo_, 0)), ebo_(std::exchange(o.ebo_, 0)),
      uvbo_(std::exchange(o.uvbo_, 0)), count_(std::exchange(o.count_, 0)) {}

GlMesh& GlMesh::operator=(GlMesh&& o) noexcept {
  if (this != &o) {
    release();
    vao_ = std::exchange(o.vao_, 0);
    vbo_ = std::exchange(o.vbo_, 0);
    ebo_ = std::exchange(o.ebo_, 0);
    uvbo_ = std::exchange(o.uvbo_, 0);
    count_ = std::exchange(o.count_, 0);
  }
  return *this;
}

void GlMesh::release() {
  if (vao_) glDeleteVertexArrays(1, &vao_);
  if (vbo_) glDeleteBuffers(1, &vbo_);
  if (ebo_) glDeleteBuffers(1, &ebo_);
  if (uvbo_) glDeleteBuffers(1, &uvbo_);
  vao_ = vbo_ = ebo_ = uvbo_ = 0;
}

void GlMesh::upload(const std::vector<Vertex>& vertices, const std::vector<std::uint32_t>& indices) {
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(Vertex)), vertices.data(), GL_DYNAMIC_DRAW);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices.size() * sizeof(std::uint32_t)), indices.data(),
               GL_DYNAMIC_DRAW);
  glBindVertexArray(0);
  count_ = int(indices.size());
}

void GlMesh::uploadTexCoords(const std::vector<glm::vec2>& texCoords) {
  glBindVertexArray(vao_);
  if (!uvbo_) glGenBuffers(1, &uvbo_);
  glBindBuffer(GL_ARRAY_BUFFER, uvbo_);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(texCoords.size() * sizeof(glm::vec2)), texCoords.data(), GL_STATIC_DRAW);
  glEnableVertexAttribArray(3);
  glVertexAttribPointer(3, 2, GL_FLOAT, GL_FALSE, GLsizei(sizeof(glm::vec2)), nullptr);
  glBindVertexArray(0);
}

void GlMesh::draw() const {
  if (count_ == 0) return;
  glBindVertexArray(vao_);
  glDrawElements(GL_TRIANGLES, count_, GL_UNSIGNED_INT, nullptr);
}

namespace {
constexpr double kTau = 2.0 * std::numbers::pi;
const glm::vec3 kWhite(1.f);
}  // namespace

void unitSphere(std::vector<Vertex>& v, std::vector<std::uint32_t>& idx, int slices, int stacks) {
  v.clear();
  idx.clear();
  for (int j = 0; j <= stacks; ++j) {
    const double phi = std::numbers::pi * double(j) / stacks;  // from +Y down
    for (int i = 0; i <= slices; ++i) {
      const double theta = kTau * double(i) / slices;
      const glm::vec3 p(float(std::sin(phi) * std::sin(theta)), float(std::cos(phi)),
                        float(std::sin(phi) * std::cos(theta)));
      v.push_back({p, p, kWhite});
    }
  }
  for (int j = 0; j < stacks; ++j)
    for (int i = 0; i < slices; ++i) {
      const auto a = std::uint32_t(j * (slices + 1) + i), b = a + std::uint32_t(slices + 1);
      idx.insert(idx.end(), {a, b, a + 1, a + 1, b, b + 1});  // counter-clockwise from outside
    }
}

void unitCylinder(std::vector<Vertex>& v, std::vector<std::uint32_t>& idx, int slices) {
  unitFrustum(v, idx, 1.f, 1.f, slices);
}

void unitFrustum(std::vector<Vertex>& v, std::vector<std::uint32_t>& idx, float bottom, float top, int slices) {
  v.clear();
  idx.clear();
  // The side's outward normal in (radial, y): (1, bottom − top), normalised (height 1).
  const float slope = bottom - top, norm = std::sqrt(1.f + slope * slope);
  for (int i = 0; i <= slices; ++i) {  // side: pairs of bottom, top
    const double theta = kTau * double(i) / slices;
    const glm::vec3 radial(float(std::sin(theta)), 0.f, float(std::cos(theta)));
    const glm::vec3 n = (radial + glm::vec3(0.f, slope, 0.f)) / norm;
    v.push_back({radial * bottom + glm::vec3(0.f, -0.5f, 0.f), n, kWhite});
    v.push_back({radial * top + glm::vec3(0.f, 0.5f, 0.f), n, kWhite});
  }
  for (int i = 0; i < slices; ++i) {
    const auto a = std::uint32_t(2 * i);
    idx.insert(idx.end(), {a, a + 2, a + 1, a + 1, a + 2, a + 3});
  }
  for (float y : {-0.5f, 0.5f}) {  // caps: a centre and a ring each
    const glm::vec3 n(0.f, y > 0.f ? 1.f : -1.f, 0.f);
    const auto centre = std::uint32_t(v.size());
    v.push_back({glm::vec3(0.f, y, 0.f), n, kWhite});
    for (int i = 0; i <= slices; ++i) {
      const double theta = kTau * double(i) / slices;
      const float r = y > 0.f ? top : bottom;
      v.push_back({glm::vec3(float(std::sin(theta)) * r, y, float(std::cos(theta)) * r), n, kWhite});
    }
    for (int i = 0; i < slices; ++i) {
      const auto a = centre + 1 + std::uint32_t(i);
      if (y > 0.f)
        idx.insert(idx.end(), {centre, a, a + 1});
      else
        idx.insert(idx.end(), {centre, a + 1, a});
    }
  }
}

void unitBox(std::vector<Vertex>& v, std::vector<std::uint32_t>& idx) {
  v.clear();
  idx.clear();
  for (int axis = 0; axis < 3; ++axis)
    for (float s : {-1.f, 1.f}) {
      glm::vec3 n(0.f);
      n[axis] = s;
      const int u = (axis + 1) % 3, w = (axis + 2) % 3;
      const auto base = std::uint32_t(v.size());
      for (int c = 0; c < 4; ++c) {
        glm::vec3 p = 0.5f * n;
        p[u] = (c == 1 || c == 2) ? 0.5f : -0.5f;
        p[w] = (c >= 2) ? 0.5f : -0.5f;
        v.push_back({p, n, kWhite});
      }
      // (u, w) is right-handed with n for s > 0: corners 0,1,2,3 run counter-clockwise.
      if (s > 0.f)
        idx.insert(idx.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
      else
        idx.insert(idx.end(), {base, base + 2, base + 1, base, base + 3, base + 2});
    }
}

}  // namespace millsim
