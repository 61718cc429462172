#pragma once
// GlMesh: one indexed triangle mesh in GPU buffers (a vertex array object
// with an interleaved vertex buffer and an index buffer). Internal to the
// graphics library; needs a current GL context for every call, including the
// destructor.
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace millsim {

struct Vertex {
  glm::vec3 position;
  glm::vec3 normal;
  glm::vec3 colour;
};

class GlMesh {
public:
  // vertexColours false: the colour attribute comes from glVertexAttrib per draw.
  explicit GlMesh(bool vertexColours = true);
  ~GlMesh();
  GlMesh(GlMesh&& other) noexcept;
  GlMesh& operator=(GlMesh&& other) noexcept;
  GlMesh(const GlMesh&) = delete;
  GlMesh& operator=(const GlMesh&) = delete;

  // Replaces the buffers' contents (re-allocating them: chunk sizes change with every remesh).
  void upload(const std::vector<Vertex>& vertices, const std::vector<std::uint32_t>& indices);
  // Texture coordinates (attribute 3), one per vertex, in a buffer of their
  // own so that the volume meshes, which have none, carry no space for them.
  void uploadTexCoords(const std::vector<glm::vec2>& texCoords);
  void draw() const;
  std::size_t triangles() const { return count_ / 3; }

private:
  void release();
  unsigned vao_ = 0, vbo_ = 0, ebo_ = 0, uvbo_ = 0;
  int count_ = 0;
};

// Unit primitives, centred on the origin: sphere of radius 1, cylinder of
// radius 1 and height 1 along Y (with caps), box of edge 1. Colour is filled
// per draw, so the vertices carry white.
void unitSphere(std::vector<Vertex>& v, std::vector<std::uint32_t>& i, int slices = 48, int stacks = 24);
void unitCylinder(std::vector<Vertex>& v, std::vector<std::uint32_t>& i, int slices = 48);
// The same height-1 solid along Y with radius `bottom` at y = −½ and `top` at y = +½.
void unitFrustum(std::vector<Vertex>& v, std::vector<std::uint32_t>& i, float bottom, float top, int slices = 48);
void unitBox(std::vector<Vertex>& v, std::vector<std::uint32_t>& i);

}  // namespace millsim
