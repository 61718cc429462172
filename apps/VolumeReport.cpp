// What `millsim check` says about each VolumeObject: size, spacing, memory,
// its densities and tissues, and point-shell counts (the shells are built for
// the report only, the three scales at once on TBB's threads: at 25 µm one
// after another they were 5 of the 13 s of `check`). Memory is resident
// memory: the grid's allocated nodes and buffers, and each shell's buffers,
// headroom for milling included, which it writes when it builds them
// (PointShell::memoryBytes); not capacity reserved and never touched.
#include <algorithm>
#include <array>
#include <iomanip>
#include <memory>
#include <sstream>

#include <tbb/parallel_for.h>

#include "VolumeReport.h"
#include "millsim/run/ThreadCpuTime.h"
#include "millsim/volume/PointShell.h"
#include "millsim/volume/TissueMap.h"
#include "millsim/volume/VolumeObject.h"
#include "millsim/volume/VoxelVolume.h"

namespace millsim::app {

std::string describeVolumes(const Scene& scene) {
  std::ostringstream out;
  out << std::fixed;
  for (VolumeObject* vo : scene.nodesOfType<VolumeObject>()) {
    const VoxelVolume* v = vo->volume();
    if (!v) continue;
    const std::string name = vo->defName().empty() ? std::string() : " '" + vo->defName() + "'";
    out << "VolumeObject" << name << ": " << vo->loadedUrl.get() << " (" << vo->format() << ")\n"
        << "  dimensions " << v->dims().x << " x " << v->dims().y << " x " << v->dims().z << " voxels, voxel size "
        << std::setprecision(4) << v->voxelSize().x * 1e3 << " x " << v->voxelSize().y * 1e3 << " x "
        << v->voxelSize().z * 1e3 << " mm\n"
        << "  active voxels " << v->activeVoxels() << ", grid " << std::setprecision(1)
        << double(v->memoryBytes()) / (1024.0 * 1024.0) << " MiB resident\n";
    // What a scene author chooses isoValue, airValue and Tissue ranges from, in the file's own numbers.
    const VoxelVolume::DensitySummary d = v->densitySummary(vo->isoValue.get());
    out << std::defaultfloat << std::setprecision(6) << "  densities above airValue " << vo->airValue.get() << ": "
        << d.voxels << " voxels";
    if (d.voxels > 0)
      out << ", " << d.min << " to " << d.max << std::setprecision(4) << " (10 / 50 / 90 %: " << d.p10 << " / " << d.p50
          << " / " << d.p90 << ")";
    out << std::setprecision(6) << "; above isoValue " << vo->isoValue.get() << ": " << d.aboveIso << "\n";
    if (const TissueMap* tissues = vo->tissueMap()) {
      out << "  tissues of those voxels:";
      for (std::size_t e = 1; e < tissues->entries().size(); ++e)
        out << " " << tissues->entries()[e].name << " " << tissues->voxelCounts()[e] << ",";
      out << " none " << tissues->voxelCounts()[0] << "\n";
    }
    out << std::fixed;
    out << "  point shell (isoValue " << std::setprecision(0) << vo->isoValue.get() << "):";
    struct Built {
      std::unique_ptr<PointShell> shell;
      double cpuMs = 0.0;  // its own build's CPU time: the builds share the cores
    };
    std::array<Built, 3> shells;
    tbb::parallel_for(0, 3, [&](int i) {
      const double t0 = threadCpuMicros();
      shells[std::size_t(i)].shell = std::make_unique<PointShell>(*v, vo->isoValue.get(), i + 1);
      shells[std::size_t(i)].cpuMs = (threadCpuMicros() - t0) * 1e-3;
    });
    for (int scale : {1, 2, 3}) {
      const Built& b = shells[std::size_t(scale - 1)];
      const double bytes = double(b.shell->memoryBytes());
      out << " scale " << scale << ": " << b.shell->size() << " points (" << std::setprecision(0) << b.cpuMs
          << " ms CPU, " << std::setprecision(1) << bytes / (1024.0 * 1024.0) << " MiB resident, "
          << std::setprecision(0) << bytes / double(std::max<std::size_t>(1, b.shell->size())) << " B/point)"
          << (scale < 3 ? ";" : "\n");
    }
  }
  return out.str();
}

}  // namespace millsim::app
