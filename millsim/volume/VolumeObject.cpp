#include "millsim/volume/VolumeObject.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>
#include <vector>

#include "millsim/volume/PointShell.h"
#include "millsim/volume/Tissue.h"
#include "millsim/volume/TissueMap.h"
#include "millsim/volume/ToothPhantom.h"
#include "millsim/volume/VolumeIO.h"
#include "millsim/volume/VoxelVolume.h"

namespace millsim {

VolumeObject::VolumeObject() = default;
VolumeObject::~VolumeObject() = default;

const NodeType& VolumeObject::type() {
  static const NodeType t = makeNodeType<VolumeObject>(
      "VolumeObject", "children", "MillSim volumes",
      "A CT voxel volume that is felt, milled and drawn, centred on its local origin.");
  return t;
}

void VolumeObject::initialize(DiagnosticSink& sink) {
  const std::filesystem::path base =
      location().file.empty() ? std::filesystem::path() : std::filesystem::path(location().file).parent_path();
  if (url.get().empty()) {
    sink.error(location(), "VolumeObject has an empty url (expected a volume file, a DICOM folder or phantom:tooth)");
    return;
  }
  if (!(isoValue.get() > airValue.get())) {
    sink.error(location(), "VolumeObject isoValue " + formatNumber(isoValue.get()) + " must be above airValue " +
                               formatNumber(airValue.get()));
    return;
  }
  std::string failures;
  std::vector<std::string> failed;
  for (const std::string& u : url.get()) {
    try {
      LoadedVolume loaded = loadVolume(u, base, airValue.get());
      const glm::dvec3 override(voxelSize.get());
      if (override != glm::dvec3(0.0)) {
        volume_ = std::make_unique<VoxelVolume>(loaded.volume.gridPtr(), loaded.volume.dims(), override,
                                                airValue.get());
      } else {
        volume_ = std::make_unique<VoxelVolume>(std::move(loaded.volume));
      }
      format_ = loaded.format;
      loadedUrl.set(u);
      // A fallback url loaded: say why each earlier one did not.
      for (const std::string& f : failed)
        sink.note(location(), "VolumeObject url failed, a later one was used: " + f);
      // A volume with nothing above isoValue is felt, milled and drawn as
      // nothing: almost always the wrong isoValue, units or voxel size.
      // Stops at the first voxel with material: a whole scan only for the volume that has none.
      float densest = -std::numeric_limits<float>::infinity();
      for (auto it = volume_->grid().cbeginValueOn(); it && !(densest > isoValue.get()); ++it)
        densest = std::max(densest, *it);
      if (!(densest > isoValue.get()))
        sink.error(location(), "VolumeObject " + u + " holds no material: no voxel is above isoValue " +
                                   formatNumber(isoValue.get()) +
                                   (std::isfinite(densest) ? " (the densest is " + formatNumber(densest) + ")"
                                                           : std::string(" (every voxel is air)")) +
                                   "; check isoValue, the data's units or the voxel size");
      classifyTissues(base, sink);
      return;
    } catch (const VolumeError& e) {
      failed.emplace_back(e.what());
      failures += "\n  " + failed.back();
    } catch (const std::bad_alloc&) {
      // A header that declares more voxels than memory holds: an error for this url, not a crash.
      failed.push_back(u + ": out of memory while reading the volume (its header declares more data than fits)");
      failures += "\n  " + failed.back();
    }
  }
  sink.error(location(), "VolumeObject could not load any of its urls:" + failures);
}

void VolumeObject::classifyTissues(const std::filesystem::path& base, DiagnosticSink& sink) {
  std::vector<const Tissue*> list;
  for (const auto& t : tissues.get()) list.push_back(t.get());
  if (list.empty()) {
    if (!labelUrl.get().empty()) sink.warning(location(), "VolumeObject has a labelUrl but no tissues; the labels are not used");
    return;
  }
  for (std::size_t i = 0; i < list.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (list[i]->name.get() == list[j]->name.get() && !list[i]->name.get().empty())
        sink.error(list[i]->location(), "Tissue name '" + list[i]->name.get() + "' is used twice in one VolumeObject");
  std::unique_ptr<VoxelVolume> labels;
  std::string failures;
  for (const std::string& u : labelUrl.get()) {
    try {
      labels = std::make_unique<VoxelVolume>(isPhantomLabelsUrl(u) ? loadPhantomLabels(u) : loadVolume(u, base, 0.f).volume);
      break;
    } catch (const VolumeError& e) {
      failures += std::string("\n  ") + e.what();
    }
  }
  if (!labelUrl.get().empty() && !labels) {
    sink.error(location(), "VolumeObject could not load any of its labelUrl volumes:" + failures);
    return;
  }
  try {
    tissueMap_ = TissueMap::build(*volume_, list, labels.get());
  } catch (const VolumeError& e) {
    sink.error(location(), std::string("VolumeObject tissues: ") + e.what());
    return;
  }
  // A tissue no voxel is made of is almost always a wrong range or label.
  const auto& counts = tissueMap_->voxelCounts();
  for (std::size_t i = 0; i < list.size(); ++i)
    if (counts[i + 1] == 0)
      sink.warning(list[i]->location(), "Tissue '" + list[i]->name.get() + "' matches no voxel of the volume");
}

glm::dvec3 VolumeObject::size() const {
  return volume_ ? glm::dvec3(volume_->dims()) * volume_->voxelSize() : glm::dvec3(0.0);
}

double VolumeObject::voxelEdge() const {
  if (!volume_) return 0.0;
  const glm::dvec3 v = volume_->voxelSize();
  return std::min({v.x, v.y, v.z});
}

PointShell& VolumeObject::pointShell(int scale) {
  auto it = shells_.find(scale);
  if (it != shells_.end()) return *it->second;
  if (!volume_) throw VolumeError("VolumeObject has no volume loaded");
  auto shell = std::make_unique<PointShell>(*volume_, isoValue.get(), scale);
  return *shells_.emplace(scale, std::move(shell)).first->second;
}

}  // namespace millsim
