#include "millsim/volume/SurfaceExport.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Morphology.h>
#include <openvdb/tools/VolumeToMesh.h>

#include "millsim/volume/TissueMap.h"
#include "millsim/volume/VoxelVolume.h"

namespace millsim {
namespace {

// The iso-surface of one grid as triangles in the volume's local frame.
// OpenVDB meshes a level set, whose inside is below the isovalue and whose
// faces face away from it; a density's inside is above, so each face is
// turned round to face out of the material.
SolidSurface surfaceOf(const VoxelVolume::Grid& grid, const VoxelVolume& volume, float iso) {
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
  openvdb::tools::volumeToMesh(grid, points, triangles, quads, double(iso), 0.0);
  SolidSurface s;
  s.vertices.reserve(points.size());
  for (const openvdb::Vec3s& p : points) {
    const openvdb::Vec3d ijk = grid.transform().worldToIndex(openvdb::Vec3d(p));
    s.vertices.push_back(glm::vec3(volume.indexToLocal(glm::dvec3(ijk.x(), ijk.y(), ijk.z()))));
  }
  s.triangles.reserve(triangles.size() + 2 * quads.size());
  for (const openvdb::Vec3I& t : triangles) s.triangles.push_back({t.x(), t.z(), t.y()});
  for (const openvdb::Vec4I& q : quads) {
    s.triangles.push_back({q.x(), q.z(), q.y()});
    s.triangles.push_back({q.x(), q.w(), q.z()});
  }
  return s;
}

// Visits every material voxel (active voxels and the voxels of active tiles).
template <typename F>
void forEachMaterialVoxel(const VoxelVolume::Grid& grid, F&& f) {
  for (auto it = grid.cbeginValueOn(); it; ++it) {
    if (it.isVoxelValue()) {
      f(it.getCoord(), *it);
      continue;
    }
    openvdb::CoordBBox box;
    it.getBoundingBox(box);
    for (auto c = box.begin(); c; ++c) f(*c, *it);
  }
}

std::string safeName(const std::string& name) {
  std::string s;
  for (const char c : name) s += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '_';
  return s.empty() ? "solid" : s;
}

// Written to FILE.tmp and renamed over FILE once whole: a failed write
// leaves no truncated mesh behind.
struct File {
  std::FILE* f;
  std::filesystem::path path, tmp;
  File(const std::filesystem::path& p, const char* mode) : f(nullptr), path(p), tmp(p.string() + ".tmp") {
    f = std::fopen(tmp.c_str(), mode);
    if (!f) throw std::runtime_error(p.string() + ": cannot open it for writing: " + std::strerror(errno));
  }
  ~File() {
    if (!f) return;
    std::fclose(f);
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
  }
  void write(const void* data, std::size_t n) {
    if (std::fwrite(data, 1, n, f) != n) fail();
  }
  void close() {
    const int r = std::fclose(f);
    f = nullptr;
    std::error_code ec;
    if (r != 0) std::filesystem::remove(tmp, ec), fail();
    std::filesystem::rename(tmp, path, ec);
    if (ec) throw std::runtime_error(path.string() + ": writing failed: " + ec.message());
  }
  [[noreturn]] void fail() const { throw std::runtime_error(path.string() + ": writing failed: " + std::strerror(errno)); }
};

constexpr float kMillimetres = 1e3f;

void writeStl(const std::vector<SolidSurface>& solids, const std::filesystem::path& path) {
  File out(path, "wb");
  char header[80] = {};
  std::snprintf(header, sizeof header, "MillSim milled surface, millimetres");
  out.write(header, sizeof header);
  const std::uint32_t n = std::uint32_t(triangleCount(solids));
  out.write(&n, 4);
  for (const SolidSurface& s : solids)
    for (const glm::uvec3& t : s.triangles) {
      const glm::vec3 a = s.vertices[t.x] * kMillimetres, b = s.vertices[t.y] * kMillimetres,
                      c = s.vertices[t.z] * kMillimetres;
      const glm::vec3 cross = glm::cross(b - a, c - a);
      const float len = glm::length(cross);
      const glm::vec3 normal = len > 0.f ? cross / len : glm::vec3(0.f);
      float record[12] = {normal.x, normal.y, normal.z, a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z};
      out.write(record, sizeof record);
      const std::uint16_t attributes = 0;
      out.write(&attributes, 2);
    }
  out.close();
}

void writeObj(const std::vector<SolidSurface>& solids, const std::filesystem::path& path) {
  std::filesystem::path mtl = path;
  mtl.replace_extension(".mtl");
  {
    File m(mtl, "w");
    std::fprintf(m.f, "# MillSim: the colours of the tissues in %s\n", path.filename().c_str());
    for (const SolidSurface& s : solids)
      std::fprintf(m.f, "newmtl %s\nKd %.4f %.4f %.4f\n", safeName(s.name).c_str(), s.colour.r, s.colour.g, s.colour.b);
    m.close();
  }
  File out(path, "w");
  std::fprintf(out.f, "# MillSim: the milled volume, an object per tissue; millimetres\nmtllib %s\n",
               mtl.filename().c_str());
  std::size_t base = 1;
  for (const SolidSurface& s : solids) {
    std::fprintf(out.f, "o %s\nusemtl %s\n", safeName(s.name).c_str(), safeName(s.name).c_str());
    for (const glm::vec3& v : s.vertices)
      std::fprintf(out.f, "v %.6g %.6g %.6g\n", v.x * kMillimetres, v.y * kMillimetres, v.z * kMillimetres);
    for (const glm::uvec3& t : s.triangles)
      std::fprintf(out.f, "f %zu %zu %zu\n", base + t.x, base + t.y, base + t.z);
    base += s.vertices.size();
  }
  if (std::ferror(out.f)) out.fail();
  out.close();
}

void writePly(const std::vector<SolidSurface>& solids, const std::filesystem::path& path) {
  std::size_t vertices = 0;
  for (const SolidSurface& s : solids) vertices += s.vertices.size();
  File out(path, "wb");
  std::string header = "ply\nformat binary_little_endian 1.0\ncomment MillSim: the milled volume, millimetres\n";
  for (const SolidSurface& s : solids)
    header += "comment solid " + safeName(s.name) + " " + std::to_string(s.triangles.size()) + " triangles\n";
  header += "element vertex " + std::to_string(vertices) +
            "\nproperty float x\nproperty float y\nproperty float z\n"
            "property uchar red\nproperty uchar green\nproperty uchar blue\n"
            "element face " + std::to_string(triangleCount(solids)) +
            "\nproperty list uchar int vertex_indices\nend_header\n";
  out.write(header.data(), header.size());
  for (const SolidSurface& s : solids) {
    unsigned char rgb[3];
    for (int i = 0; i < 3; ++i) rgb[i] = static_cast<unsigned char>(std::lround(std::clamp(s.colour[i], 0.f, 1.f) * 255.f));
    for (const glm::vec3& v : s.vertices) {
      const float xyz[3] = {v.x * kMillimetres, v.y * kMillimetres, v.z * kMillimetres};
      out.write(xyz, sizeof xyz);
      out.write(rgb, 3);
    }
  }
  std::uint32_t base = 0;
  for (const SolidSurface& s : solids) {
    for (const glm::uvec3& t : s.triangles) {
      unsigned char record[13];
      record[0] = 3;
      const std::int32_t idx[3] = {std::int32_t(base + t.x), std::int32_t(base + t.y), std::int32_t(base + t.z)};
      std::memcpy(record + 1, idx, sizeof idx);
      out.write(record, sizeof record);
    }
    base += std::uint32_t(s.vertices.size());
  }
  out.close();
}

std::string lowerExtension(const std::filesystem::path& file) {
  std::string e = file.extension().string();
  for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

}  // namespace

std::size_t triangleCount(const std::vector<SolidSurface>& solids) {
  std::size_t n = 0;
  for (const SolidSurface& s : solids) n += s.triangles.size();
  return n;
}

std::vector<SolidSurface> extractSolids(const VoxelVolume& density, float isoValue, const TissueMap* tissues,
                                        SolidSplit split) {
  openvdb::initialize();
  std::vector<SolidSurface> out;
  if (split == SolidSplit::Whole || !tissues) {
    SolidSurface s = surfaceOf(density.grid(), density, isoValue);
    s.name = "material";
    if (!s.triangles.empty()) out.push_back(std::move(s));
    return out;
  }
  // Each tissue's voxels in a grid of their own, the rest air; one pass over
  // the material, each voxel written once.
  const std::vector<TissueMap::Entry>& entries = tissues->entries();
  std::vector<VoxelVolume::Grid::Ptr> grids(entries.size());
  std::vector<VoxelVolume::Grid::Accessor> at;
  for (auto& g : grids) {
    g = VoxelVolume::Grid::create(density.airValue());
    g->setTransform(density.grid().transform().copy());
    at.push_back(g->getAccessor());
  }
  auto labels = tissues->labels().getConstAccessor();
  forEachMaterialVoxel(density.grid(), [&](const openvdb::Coord& c, float v) {
    const int label = labels.getValue(c);
    if (label >= 0 && std::size_t(label) < at.size()) at[std::size_t(label)].setValue(c, v);
  });
  auto material = density.grid().getConstAccessor();
  // Tissue 1 first, unclassified material last: the order a scene lists them.
  for (std::size_t k = 1; k <= entries.size(); ++k) {
    const std::size_t e = k % entries.size();
    const TissueMap::Entry& entry = entries[e];
    float iso = isoValue;
    // A soft tissue's voxels lie below the isoValue: its surface is half-way
    // to what it was before milling, as the cut plane's section draws it.
    if (entry.soft && std::isfinite(entry.densityBelowSurface))
      iso = std::min(isoValue, 0.5f * (density.airValue() + entry.densityBelowSurface));
    // The voxels round the tissue, for the mesher's cells: another tissue's
    // material there is mirrored about the isoValue (2·iso − d). Two tissues
    // then cross the isoValue at the same point of the edge between them,
    // each from its side, so their solids meet without gap or overlap;
    // masking the other tissue to air would put each surface at its own
    // density's crossing, and a dense enamel would overlap a lighter dentin.
    openvdb::tools::dilateActiveValues(grids[e]->tree(), 1, openvdb::tools::NN_FACE_EDGE_VERTEX,
                                       openvdb::tools::EXPAND_TILES);
    for (auto it = grids[e]->beginValueOn(); it; ++it) {
      const openvdb::Coord c = it.getCoord();
      if (std::size_t(labels.getValue(c)) == e) continue;
      const float d = material.getValue(c);
      it.setValue(d > iso ? 2.f * iso - d : d);
    }
    SolidSurface s = surfaceOf(*grids[e], density, iso);
    s.name = e == 0 ? "material" : entry.name;
    s.colour = entry.colour;
    if (!s.triangles.empty()) out.push_back(std::move(s));
  }
  return out;
}

bool isMeshOutput(const std::filesystem::path& file) {
  const std::string e = lowerExtension(file);
  return e == ".stl" || e == ".obj" || e == ".ply";
}

SolidSplit splitFor(const std::filesystem::path& file) {
  return lowerExtension(file) == ".stl" ? SolidSplit::Whole : SolidSplit::PerTissue;
}

void writeSolids(const std::vector<SolidSurface>& solids, const std::filesystem::path& file) {
  const std::string e = lowerExtension(file);
  if (triangleCount(solids) > std::size_t(INT32_MAX))
    throw std::runtime_error(file.string() + ": " + std::to_string(triangleCount(solids)) +
                             " triangles are more than a mesh file holds");
  if (e == ".stl") return writeStl(solids, file);
  if (e == ".obj") return writeObj(solids, file);
  if (e == ".ply") return writePly(solids, file);
  throw std::runtime_error(file.string() + ": a mesh is written as .stl, .obj or .ply");
}

}  // namespace millsim
