#pragma once
// TriangleMesh: a Shape's geometry as graphics draws it when it is not one of
// the unit primitives — an IndexedFaceSet, an IndexedTriangleSet, a Cone, or a
// primitive that carries a texture. Local frame, no OpenGL; every three
// consecutive vertices are one triangle (corners are not shared: a mesh's
// faces may each have their own normal, colour and texture coordinate).
#include <cstddef>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace millsim {

struct TriangleMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;    // unit length, one per position
  std::vector<glm::vec3> colours;    // one per position, or empty: the Material's diffuseColor
  std::vector<glm::vec2> texCoords;  // one per position, or empty: no texture coordinates
  glm::vec3 boundsMin{0.f}, boundsMax{0.f};

  std::size_t triangles() const { return positions.size() / 3; }
  // Sets boundsMin and boundsMax from the positions (left as they are without any).
  void computeBounds() {
    if (positions.empty()) return;
    boundsMin = boundsMax = positions.front();
    for (const glm::vec3& p : positions) boundsMin = glm::min(boundsMin, p), boundsMax = glm::max(boundsMax, p);
  }
};

}  // namespace millsim
