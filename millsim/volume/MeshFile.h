#pragma once
// MeshFile: the surface meshes dental scanners and CAD write — STL (ASCII and
// binary), OBJ (its `o`/`g` groups are parts), PLY (ASCII, binary little and
// big endian) — as closed parts ready to voxelise (MeshVolume.h).
//
// Read by hand, not with a general importer: each format is a few dozen lines
// here, bounded on hostile input (counts checked against the file's size
// before anything is allocated, lines read with a cap, at most
// kMaxMeshTriangles), while assimp's OBJ and PLY importers had heap overflows
// found by OSS-Fuzz after the release Debian 12 ships (5.2.5), and a library
// we cannot patch does not read untrusted bytes in a process that runs a
// haptic loop (docs/architecture.md, "Hostile input").
//
// Coordinates are as the file writes them: the formats carry no unit. Corners
// at the same position are one vertex, so that open edges can be counted.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace millsim {

// Dental scans have a few hundred thousand to two million triangles; reading
// one costs about 100 bytes a triangle on the way (corners, welding, edges).
inline constexpr std::uint64_t kMaxMeshTriangles = 10'000'000;
// Parts of one mesh (each is meshed on its own): enamel, dentin, pulp, …
inline constexpr std::size_t kMaxMeshParts = 1000;

struct MeshPart {
  std::string name;  // the OBJ group or object, the ASCII STL solid; else the file's stem
  std::vector<glm::vec3> vertices;
  std::vector<glm::uvec3> triangles;  // indices into vertices, none degenerate
};

// An edge used by one triangle only: where a part is not closed.
struct OpenEdges {
  std::size_t count = 0;
  glm::vec3 from{0.f}, to{0.f};  // the first one found
  // The largest hole: the open edges joined into loops, the widest loop's
  // hydraulic diameter (4 × its vector area / its length) — a crack between
  // two faces that meet (a T-junction) is as wide as its faces are apart, a
  // missing square face as wide as its side. It assumes the part's triangles
  // wind one way round; mixed winding can make a hole look narrower.
  double widestGap = 0.0;
};

struct SurfaceMesh {
  std::string format;  // "STL", "binary STL", "OBJ", "PLY"
  std::vector<MeshPart> parts;
  std::size_t triangleCount() const;
};

bool isMeshFile(const std::filesystem::path& file);  // .stl, .obj or .ply (any case)
// Throws VolumeError "FILE[:LINE]: what is wrong" on anything it cannot read.
SurfaceMesh readSurfaceMesh(const std::filesystem::path& file);
OpenEdges openEdges(const MeshPart& part);
// The volume the part encloses (|signed volume|, divergence theorem), in the file's units cubed.
double enclosedVolume(const MeshPart& part);

}  // namespace millsim
