// OpenVDB .vdb files: readVdb and writeVdb.
//
// The grid's index space is our index space (voxel (i, j, k) is grid coordinate
// (i, j, k)); its transform gives the voxel size in millimetres. Files written
// here hold one FloatGrid named "density" and the metadata "millsim_dims" (the
// volume's dimensions, which the active voxels alone cannot tell when the
// border is air).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include "millsim/volume/VolumeIO.h"

namespace fs = std::filesystem;

namespace millsim {

namespace {

const char* const kDimsMeta = "millsim_dims";

std::string gridList(const openvdb::GridPtrVec& grids) {
  std::string s;
  for (const auto& g : grids) {
    if (!s.empty()) s += ", ";
    s += "'" + g->getName() + "' (" + g->valueType() + ")";
  }
  return s.empty() ? "none" : s;
}

void refuseOversizedGrid(const std::string& name, const openvdb::GridBase& grid) {
  const auto lo = grid.getMetadata<openvdb::Vec3IMetadata>(openvdb::GridBase::META_FILE_BBOX_MIN);
  const auto hi = grid.getMetadata<openvdb::Vec3IMetadata>(openvdb::GridBase::META_FILE_BBOX_MAX);
  if (lo && hi) {
    std::uint64_t voxels = 1;
    for (int a = 0; a < 3; ++a) {
      const std::int64_t extent = std::int64_t(hi->value()[a]) - std::int64_t(lo->value()[a]) + 1;
      voxels = extent <= 0 ? 0 : std::min<std::uint64_t>(voxels * std::uint64_t(extent), kMaxVoxels + 1);
    }
    if (voxels > kMaxVoxels) {
      std::ostringstream m;
      m << name << ": grid '" << grid.getName() << "' spans " << lo->value() << " to " << hi->value()
        << ", more than the limit of " << kMaxVoxels << " voxels";
      throw VolumeError(m.str());
    }
  }
  // A dense float grid of kMaxVoxels is 4 GiB; twice that leaves room for the tree.
  const std::int64_t limit = std::int64_t(kMaxVoxels) * 8;
  if (const auto mem = grid.getMetadata<openvdb::Int64Metadata>(openvdb::GridBase::META_FILE_MEM_BYTES);
      mem && mem->value() > limit)
    throw VolumeError(name + ": grid '" + grid.getName() + "' needs " + std::to_string(mem->value()) +
                      " bytes in memory, more than the " + std::to_string(limit) + " a volume may take");
}

}  // namespace

VoxelVolume readVdb(const fs::path& file, float airValue) {
  const std::string name = file.string();
  requireFile(file, "a .vdb file");
  openvdb::initialize();

  openvdb::GridPtrVecPtr grids;
  try {
    openvdb::io::File f(name);
    f.open(/*delayLoad=*/false);  // read everything now, so that a bad file fails here
    // The statistics OpenVDB writes with every grid (bounding box, memory)
    // are read without the trees, so a grid far larger than a volume may be
    // is refused before its tree is allocated. A file without them (or one
    // that lies) is still bounded by the voxel-count check below.
    const openvdb::GridPtrVecPtr described = f.readAllGridMetadata();  // kept: the loop must not outlive it
    for (const auto& g : *described) refuseOversizedGrid(name, *g);
    grids = f.getGrids();
    f.close();
  } catch (const VolumeError&) {
    throw;
  } catch (const std::exception& e) {
    throw VolumeError(name + ": cannot read as an OpenVDB file: " + e.what());
  }

  // The grid named "density" if it is a FloatGrid, else the first FloatGrid.
  openvdb::FloatGrid::Ptr grid;
  for (const auto& g : *grids)
    if (g->getName() == "density" && g->isType<openvdb::FloatGrid>()) grid = openvdb::gridPtrCast<openvdb::FloatGrid>(g);
  for (const auto& g : *grids)
    if (!grid && g->isType<openvdb::FloatGrid>()) grid = openvdb::gridPtrCast<openvdb::FloatGrid>(g);
  if (!grid) throw VolumeError(name + ": no float grid in the file (grids: " + gridList(*grids) + ")");

  if (!grid->transform().isLinear())
    throw VolumeError(name + ": grid '" + grid->getName() + "' has a non-linear (frustum) transform; only linear transforms are supported");
  const openvdb::Vec3d vs = grid->voxelSize();  // millimetres
  glm::dvec3 spacingMm(vs.x(), vs.y(), vs.z());
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(spacingMm[a]) || spacingMm[a] <= 0.0) {
      std::ostringstream m;
      m << name << ": voxel spacing along " << "xyz"[a] << " is " << spacingMm[a]
        << " mm; spacing must be a positive finite number of millimetres";
      throw VolumeError(m.str());
    }

  glm::ivec3 dims;
  if (auto meta = grid->getMetadata<openvdb::Vec3IMetadata>(kDimsMeta)) {
    const openvdb::Vec3i d = meta->value();
    dims = glm::ivec3(d.x(), d.y(), d.z());
  } else {
    const openvdb::CoordBBox box = grid->evalActiveVoxelBoundingBox();
    if (box.empty())
      throw VolumeError(name + ": grid '" + grid->getName() + "' has no active voxels and no " + kDimsMeta +
                        " metadata, so its dimensions are unknown");
    if (box.min().x() < 0 || box.min().y() < 0 || box.min().z() < 0) {
      std::ostringstream m;
      m << name << ": grid '" << grid->getName() << "' has active voxels at negative indices (bounding box " << box
        << "); the volume must start at index (0, 0, 0)";
      throw VolumeError(m.str());
    }
    dims = glm::ivec3(box.max().x() + 1, box.max().y() + 1, box.max().z() + 1);
  }
  const glm::dvec3 spacing = spacingMm / 1000.0;
  checkVolumeShape(name, dims, spacing);

  // Dense copy: active values as they are, inactive voxels take the file's background.
  const std::size_t n = std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z);
  std::vector<float> values(n, grid->background());
  const openvdb::CoordBBox volumeBox(openvdb::Coord(0), openvdb::Coord(dims.x - 1, dims.y - 1, dims.z - 1));
  for (auto it = grid->cbeginValueOn(); it; ++it) {
    openvdb::CoordBBox b;
    it.getBoundingBox(b);
    b.intersect(volumeBox);
    if (b.empty()) continue;
    const float v = *it;
    for (int k = b.min().z(); k <= b.max().z(); ++k)
      for (int j = b.min().y(); j <= b.max().y(); ++j)
        for (int i = b.min().x(); i <= b.max().x(); ++i)
          values[(std::size_t(k) * std::size_t(dims.y) + std::size_t(j)) * std::size_t(dims.x) + std::size_t(i)] = v;
  }
  return VoxelVolume::fromDense(values.data(), dims, spacing, airValue);
}

void writeVdb(const VoxelVolume& volume, const fs::path& file) {
  const std::string name = file.string();
  openvdb::initialize();
  // A new grid sharing the volume's tree: the volume itself is not touched.
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(volume.gridPtr()->treePtr());
  grid->setName("density");
  const glm::dvec3 mm = volume.voxelSize() * 1000.0;
  auto xform = openvdb::math::Transform::createLinearTransform(1.0);
  xform->preScale(openvdb::Vec3d(mm.x, mm.y, mm.z));
  grid->setTransform(xform);
  const glm::ivec3 d = volume.dims();
  grid->insertMeta(kDimsMeta, openvdb::Vec3IMetadata(openvdb::Vec3i(d.x, d.y, d.z)));
  try {
    openvdb::io::File f(name);
    f.write(openvdb::GridCPtrVec{grid});
    f.close();
  } catch (const std::exception& e) {
    throw VolumeError(name + ": cannot write the OpenVDB file: " + e.what());
  }
}

}  // namespace millsim
