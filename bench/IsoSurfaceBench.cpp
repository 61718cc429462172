// Iso-surface mesher costs on the full-size tooth phantom (256×256×176,
// 0.1 mm): a full build per chunk size, whole-volume vtkFlyingEdges3D for
// reference, and re-meshing the chunks dirtied by one milling-sized stamp.
//   iso_surface_bench --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include <algorithm>
#include <memory>
#include <set>
#include <vector>

#include <glm/geometric.hpp>
#include <vtkFlyingEdges3D.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>

#include "millsim/volume/IsoSurface.h"
#include "millsim/volume/ToothPhantom.h"

namespace {

using millsim::IsoSurfaceMesher;
using millsim::VoxelVolume;

constexpr float kIso = 700.f;          // VolumeObject's default isoValue
constexpr double kStampRadius = 10.0;  // voxels: a 2 mm burr at 0.1 mm voxels

// Built once: the phantom takes a second or two.
VoxelVolume& tooth() {
  static auto volume = std::make_unique<VoxelVolume>(millsim::makeToothPhantom(millsim::ToothPhantomOptions{}));
  return *volume;
}

void BM_FullBuild(benchmark::State& state) {
  const int chunkSize = int(state.range(0));
  IsoSurfaceMesher mesher(tooth(), kIso, chunkSize);
  for (auto _ : state) {
    mesher.buildAll();
    benchmark::DoNotOptimize(mesher.chunkCount());
  }
  state.counters["chunks"] = double(mesher.chunkCount());
  state.counters["triangles"] = double(mesher.triangleCount());
}
BENCHMARK(BM_FullBuild)->Arg(8)->Arg(16)->Arg(32)->Unit(benchmark::kMillisecond);

void BM_WholeVolumeFlyingEdges(benchmark::State& state) {
  const VoxelVolume& v = tooth();
  const glm::ivec3 d = v.dims();
  vtkNew<vtkImageData> image;
  image->SetExtent(0, d.x - 1, 0, d.y - 1, 0, d.z - 1);
  image->SetSpacing(v.voxelSize().x, v.voxelSize().y, v.voxelSize().z);
  vtkNew<vtkFloatArray> s;
  s->SetNumberOfTuples(vtkIdType(d.x) * d.y * d.z);
  auto acc = v.grid().getConstAccessor();
  vtkIdType n = 0;
  for (int k = 0; k < d.z; ++k)
    for (int j = 0; j < d.y; ++j)
      for (int i = 0; i < d.x; ++i) s->SetValue(n++, acc.getValue(openvdb::Coord(i, j, k)));
  image->GetPointData()->SetScalars(s);
  vtkNew<vtkFlyingEdges3D> fe;
  fe->SetInputData(image);
  fe->SetValue(0, kIso);
  fe->ComputeNormalsOn();
  for (auto _ : state) {
    fe->Modified();
    fe->Update();
    benchmark::DoNotOptimize(fe->GetOutput()->GetNumberOfCells());
  }
  state.counters["triangles"] = double(fe->GetOutput()->GetNumberOfCells());
}
BENCHMARK(BM_WholeVolumeFlyingEdges)->Unit(benchmark::kMillisecond);

// Nine stamps on the occlusal surface (around the highest vertex, where a
// tool coming from above first touches; offset by 0, 7 and 13 voxels so they
// sit differently against chunk borders), carved once; each iteration
// re-meshes the chunks one of them dirtied, in turn: the graphics cost per stamp.
void BM_StampUpdate(benchmark::State& state) {
  const int chunkSize = int(state.range(0));
  // A private copy: the stamps must not change the volume the other benchmarks use.
  VoxelVolume volume(tooth().grid().deepCopy(), tooth().dims(), tooth().voxelSize(), tooth().airValue());
  IsoSurfaceMesher mesher(volume, kIso, chunkSize);
  mesher.buildAll();
  glm::vec3 top(0.f, -1e9f, 0.f);
  for (const auto& [key, c] : mesher.chunks())
    for (const auto& p : c.positions)
      if (p.y > top.y) top = p;
  const glm::ivec3 topIndex(glm::round(volume.localToIndex(glm::dvec3(top))));

  std::vector<std::vector<millsim::BlockOrigin>> stamps;
  auto acc = volume.grid().getAccessor();
  for (int dx : {0, 7, -13})
    for (int dz : {0, -7, 13}) {
      // Down the column from the top of the volume to the first material.
      const int i = topIndex.x + dx, k = topIndex.z + dz;
      int j = volume.dims().y - 1;
      while (j > 0 && acc.getValue(openvdb::Coord(i, j, k)) < kIso) --j;
      const glm::dvec3 centre(i, j, k);
      std::set<openvdb::Coord> leaves;
      const glm::ivec3 lo(glm::floor(centre - kStampRadius)), hi(glm::ceil(centre + kStampRadius));
      for (int z = lo.z; z <= hi.z; ++z)
        for (int y = lo.y; y <= hi.y; ++y)
          for (int x = lo.x; x <= hi.x; ++x)
            if (glm::length(glm::dvec3(x, y, z) - centre) <= kStampRadius) {
              acc.setValueOff(openvdb::Coord(x, y, z), volume.airValue());
              leaves.insert(openvdb::Coord(x & ~7, y & ~7, z & ~7));
            }
      std::vector<millsim::BlockOrigin>& origins = stamps.emplace_back();
      for (const openvdb::Coord& c : leaves) origins.emplace_back(c.x(), c.y(), c.z());
    }

  std::size_t n = 0, chunks = 0, leaves = 0, triangles = 0;
  for (auto _ : state) {
    const auto& dirty = stamps[n++ % stamps.size()];
    const auto changed = mesher.update(dirty);
    state.PauseTiming();  // what graphics would re-upload
    chunks += changed.size();
    leaves += dirty.size();
    for (const auto& key : changed)
      if (const auto* c = mesher.chunk(key)) triangles += c->indices.size() / 3;
    state.ResumeTiming();
  }
  state.counters["dirty_leaves"] = double(leaves) / double(n);
  state.counters["chunks_remeshed"] = double(chunks) / double(n);
  state.counters["triangles_reuploaded"] = double(triangles) / double(n);
}
BENCHMARK(BM_StampUpdate)->Arg(8)->Arg(16)->Arg(32)->Unit(benchmark::kMillisecond);

}  // namespace
