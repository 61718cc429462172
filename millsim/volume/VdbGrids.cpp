// readVdbGrids (VdbGrids.h).
#include "millsim/volume/VdbGrids.h"

#include <algorithm>
#include <filesystem>
#include <sstream>

#include <openvdb/io/File.h>

#include "millsim/volume/VolumeError.h"

namespace millsim {

namespace {

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
  if (const auto mem = grid.getMetadata<openvdb::Int64Metadata>(openvdb::GridBase::META_FILE_MEM_BYTES);
      mem && mem->value() > kMaxGridBytes)
    throw VolumeError(name + ": grid '" + grid.getName() + "' needs " + std::to_string(mem->value()) +
                      " bytes in memory, more than the " + std::to_string(kMaxGridBytes) + " a volume may take");
}

}  // namespace

int vdbReadSeconds(const std::string& name) {
  std::error_code ec;
  const std::uintmax_t bytes = std::filesystem::file_size(name, ec);
  return 60 + int(ec ? 0 : std::min<std::uintmax_t>(bytes >> 20, 1 << 20));
}

// The statistics OpenVDB writes with every grid (bounding box, memory) are
// read without the trees, so a grid far larger than a volume may be is refused
// before its tree is allocated. A file without them (or one that lies) is
// still bounded by readVdb's voxel-count check.
openvdb::GridPtrVecPtr readVdbGrids(const std::string& name) {
  try {
    openvdb::io::File f(name);
    f.open(/*delayLoad=*/false);  // read everything now, so that a bad file fails here
    const openvdb::GridPtrVecPtr described = f.readAllGridMetadata();  // kept: the loop must not outlive it
    for (const auto& g : *described) refuseOversizedGrid(name, *g);
    openvdb::GridPtrVecPtr grids = f.getGrids();
    f.close();
    return grids;
  } catch (const VolumeError&) {
    throw;
  } catch (const std::exception& e) {
    throw VolumeError(name + ": cannot read as an OpenVDB file: " + e.what());
  }
}

}  // namespace millsim
