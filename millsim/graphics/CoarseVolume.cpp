#include "millsim/graphics/CoarseVolume.h"

#include <stdexcept>

#include <glm/common.hpp>

#include "millsim/volume/VoxelVolume.h"

namespace millsim {

namespace {

using Grid = VoxelVolume::Grid;

// Coarse voxels [from, to] (already clamped) through the given accessors.
void average(const VoxelVolume& fine, Grid::ConstAccessor& in, Grid::Accessor& out, int f, glm::ivec3 from,
             glm::ivec3 to) {
  const glm::ivec3 last = fine.dims() - 1;
  const float air = fine.airValue(), scale = 1.f / float(f * f * f);
  for (int k = from.z; k <= to.z; ++k)
    for (int j = from.y; j <= to.y; ++j)
      for (int i = from.x; i <= to.x; ++i) {
        float sum = 0.f;
        for (int z = 0; z < f; ++z)
          for (int y = 0; y < f; ++y)
            for (int x = 0; x < f; ++x) {
              const glm::ivec3 v = glm::min(f * glm::ivec3(i, j, k) + glm::ivec3(x, y, z), last);
              sum += in.getValue(openvdb::Coord(v.x, v.y, v.z));
            }
        const float mean = scale * sum;
        if (mean != air)
          out.setValue(openvdb::Coord(i, j, k), mean);
        else
          out.setValueOff(openvdb::Coord(i, j, k), air);
      }
}

}  // namespace

glm::ivec3 coarseDims(glm::ivec3 fine, int factor) { return (fine + factor - 1) / factor; }

void averageBlocks(const VoxelVolume& fine, VoxelVolume& coarse, int factor, glm::ivec3 from, glm::ivec3 to) {
  from = glm::max(from, glm::ivec3(0));
  to = glm::min(to, coarse.dims() - 1);
  auto in = fine.grid().getConstAccessor();
  auto out = coarse.grid().getAccessor();
  average(fine, in, out, factor, from, to);
}

void averageAll(const VoxelVolume& fine, VoxelVolume& coarse, int factor) {
  if (factor != 2 && factor != 4 && factor != 8)
    throw std::invalid_argument("averageAll: factor " + std::to_string(factor) + " (expected 2, 4 or 8)");
  auto in = fine.grid().getConstAccessor();
  auto out = coarse.grid().getAccessor();
  const glm::ivec3 top = coarse.dims() - 1;
  const float air = fine.airValue();
  auto region = [&](const openvdb::Coord& lo, const openvdb::Coord& hi) {
    const glm::ivec3 from = glm::max(glm::ivec3(lo.x(), lo.y(), lo.z()) / factor, glm::ivec3(0));
    const glm::ivec3 to = glm::min(glm::ivec3(hi.x(), hi.y(), hi.z()) / factor, top);
    if (glm::all(glm::lessThanEqual(from, to))) average(fine, in, out, factor, from, to);
  };
  // Every leaf, whatever its voxels hold (air in a leaf averages to air, as the box would).
  for (auto leaf = fine.grid().tree().cbeginLeaf(); leaf; ++leaf) {
    const openvdb::Coord o = leaf->origin();
    region(o, o.offsetBy(7));
  }
  // Tiles above the leaves (a block of solid material) that are not air.
  auto tile = fine.grid().tree().cbeginValueAll();
  tile.setMaxDepth(Grid::TreeType::DEPTH - 2);
  for (; tile; ++tile) {
    if (!tile.isTileValue() || *tile == air) continue;
    const openvdb::CoordBBox box = tile.getBoundingBox();
    region(box.min(), box.max());
  }
}

}  // namespace millsim
