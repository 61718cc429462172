// What `millsim check` says about each VolumeObject: size, spacing, memory,
// its densities and tissues, and point-shell counts (the shells are built for
// the report only; each build uses every core itself). Memory is resident
// memory: the grid's allocated nodes and buffers, and each shell's buffers,
// headroom for milling included, which it writes when it builds them
// (PointShell::memoryBytes); not capacity reserved and never touched.
#include <algorithm>
#include <chrono>
#include <iomanip>
#include <sstream>

#include "VolumeReport.h"
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
    for (int scale : {1, 2, 3}) {
      const auto t0 = std::chrono::steady_clock::now();
      const PointShell shell(*v, vo->isoValue.get(), scale);
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      const double bytes = double(shell.memoryBytes());
      out << " scale " << scale << ": " << shell.size() << " points (" << std::setprecision(0) << ms << " ms, "
          << std::setprecision(1) << bytes / (1024.0 * 1024.0) << " MiB resident, " << std::setprecision(0)
          << bytes / double(std::max<std::size_t>(1, shell.size())) << " B/point)" << (scale < 3 ? ";" : "\n");
    }
  }
  return out.str();
}

}  // namespace millsim::app
