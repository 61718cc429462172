#pragma once
// SurfaceExport: the milled volume's surface as closed triangle meshes — the
// whole material's, or one solid per tissue — and writers for STL, OBJ and
// PLY, so that a trainee's preparation can be compared with an ideal one in
// any mesh tool (`--save-mesh`), and a saved .obj loads back as a mesh url.
//
// What a solid is: the surface density == isoValue of the voxels (samples at
// voxel centres, as graphics meshes them), extracted with OpenVDB's
// volumeToMesh over the sparse grid. Unlike the graphics mesh it is closed
// where material reaches the data's border (outside the grid is air). A
// tissue's solid is that surface of the voxels labelled with it; two hard
// tissues' solids meet without gap or overlap; a soft tissue (the pulp), whose
// density is below the isoValue, is drawn at its own level, as far as milling
// left its original density (as a cut plane's section draws it), a fraction
// of a voxel inside the cavity its neighbours leave.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace millsim {

class VoxelVolume;
class TissueMap;

struct SolidSurface {
  std::string name;                   // the tissue's, or "material"
  glm::vec3 colour{0.85f, 0.8f, 0.7f};  // the Tissue's colour, 0..1
  std::vector<glm::vec3> vertices;    // the volume's local frame (centred), metres
  std::vector<glm::uvec3> triangles;  // counter-clockwise seen from outside
};

enum class SolidSplit {
  Whole,      // one solid: all material above the isoValue (a soft tissue is a cavity in it)
  PerTissue,  // a solid per tissue that has material (unclassified material is "material")
};

// Not thread-safe with milling: nothing may write the voxels meanwhile.
// `tissues` may be null (then PerTissue gives the whole as "material").
std::vector<SolidSurface> extractSolids(const VoxelVolume& density, float isoValue, const TissueMap* tissues,
                                        SolidSplit split);

// .stl, .obj or .ply (any case).
bool isMeshOutput(const std::filesystem::path& file);
// How writeSolids stores solids in a file of that extension: STL has no
// parts, so an .stl gets the whole surface; .obj and .ply a solid per tissue.
SolidSplit splitFor(const std::filesystem::path& file);

// Writes by the extension, in millimetres (as dental scanners and CAD write
// meshes; load it back with meshUnit='0.001'):
//   .stl  binary STL, every solid in one (STL carries neither parts nor colour);
//   .obj  an `o` object and `usemtl` per solid, with FILE.mtl of their colours;
//   .ply  binary little-endian PLY, each vertex in its solid's colour, and a
//         comment line per solid naming it.
// Throws std::runtime_error naming the file when it cannot be written.
void writeSolids(const std::vector<SolidSurface>& solids, const std::filesystem::path& file);

std::size_t triangleCount(const std::vector<SolidSurface>& solids);

}  // namespace millsim
