// The voxel side of VolumeObject (VolumeModule.h): loading its url and label
// volumes, the check that it holds material, its tissues and point shells.
// In libmillsim, which links OpenVDB; the node itself is in libmillsim_scene.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <future>
#include <limits>
#include <map>
#include <new>
#include <optional>
#include <system_error>
#include <vector>

#include "millsim/core/Progress.h"
#include "millsim/volume/MeshFile.h"
#include "millsim/volume/MeshVolume.h"
#include "millsim/volume/PointShell.h"
#include "millsim/volume/Tissue.h"
#include "millsim/volume/TissueMap.h"
#include "millsim/volume/ToothPhantom.h"
#include "millsim/volume/VolumeContents.h"
#include "millsim/volume/VolumeIO.h"
#include "millsim/volume/VolumeModule.h"
#include "millsim/volume/VolumeObject.h"
#include "millsim/volume/VoxelVolume.h"

namespace millsim {

namespace {

// "VolumeObject 'Tooth'", as progress names it.
std::string name(const VolumeObject& node) {
  return "VolumeObject" + (node.defName().empty() ? std::string() : " '" + node.defName() + "'");
}

// A VolumeObject's labels: the first of its labelUrl volumes that loads, or
// why none did (one line per url).
struct LabelsRead {
  std::unique_ptr<VoxelVolume> labels;
  std::string failures;
};

LabelsRead readLabels(const std::vector<std::string>& urls, const std::filesystem::path& base) {
  LabelsRead read;
  for (const std::string& u : urls) {
    try {
      read.labels = std::make_unique<VoxelVolume>(isPhantomLabelsUrl(u) ? loadPhantomLabels(u) : loadVolume(u, base, 0.f).volume);
      break;
    } catch (const VolumeError& e) {
      read.failures += std::string("\n  ") + e.what();
    }
  }
  return read;
}

class VoxelContents final : public VolumeContents {
public:
  VoxelContents(VoxelVolume volume, std::string format, float isoValue)
      : volume_(std::move(volume)), format_(std::move(format)), isoValue_(isoValue) {}
  // A mesh's parts, as labels the Tissues choose by name (or label).
  void setParts(VoxelVolume labels, std::vector<std::string> parts) {
    partLabels_ = std::make_unique<VoxelVolume>(std::move(labels));
    parts_ = std::move(parts);
  }
  VoxelVolume& voxels() override { return volume_; }
  const VoxelVolume& voxels() const override { return volume_; }
  const std::string& format() const override { return format_; }
  glm::dvec3 size() const override { return glm::dvec3(volume_.dims()) * volume_.voxelSize(); }
  glm::dvec3 voxelEdges() const override { return volume_.voxelSize(); }
  PointShell& pointShell(int scale) override {
    auto it = shells_.find(scale);
    if (it != shells_.end()) return *it->second;
    auto shell = std::make_unique<PointShell>(volume_, isoValue_, scale);
    return *shells_.emplace(scale, std::move(shell)).first->second;
  }
  bool hasPointShell(int scale) const override { return shells_.count(scale) != 0; }
  // The labels being read on another thread since before the densities were.
  void setLabelsAhead(std::future<LabelsRead> ahead) { labelsAhead_ = std::move(ahead); }
  // The labels of `url`, already made with the densities (the phantom's).
  void setPreloadedLabels(std::string url, VoxelVolume labels) {
    preloadedUrl_ = std::move(url);
    preloaded_ = std::make_unique<VoxelVolume>(std::move(labels));
  }
  const TissueMap* tissueMap() const override { return tissueMap_.get(); }
  void classifyTissues(const VolumeObject& node, const std::filesystem::path& base, DiagnosticSink& sink);

private:
  VoxelVolume volume_;
  std::string format_;
  float isoValue_;
  std::map<int, std::unique_ptr<PointShell>> shells_;
  std::unique_ptr<TissueMap> tissueMap_;
  std::unique_ptr<VoxelVolume> partLabels_;
  std::vector<std::string> parts_;
  std::string preloadedUrl_;
  std::unique_ptr<VoxelVolume> preloaded_;
  std::future<LabelsRead> labelsAhead_;
};

void VoxelContents::classifyTissues(const VolumeObject& node, const std::filesystem::path& base, DiagnosticSink& sink) {
  std::vector<const Tissue*> list;
  for (const auto& t : node.tissues.get()) list.push_back(t.get());
  if (list.empty()) {
    if (!node.labelUrl.get().empty()) sink.warning(node.location(), "VolumeObject has a labelUrl but no tissues; the labels are not used");
    return;
  }
  for (std::size_t i = 0; i < list.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (list[i]->name.get() == list[j]->name.get() && !list[i]->name.get().empty())
        sink.error(list[i]->location(), "Tissue name '" + list[i]->name.get() + "' is used twice in one VolumeObject");
  std::unique_ptr<VoxelVolume> labels;
  std::string failures;
  // A mesh labels itself by its parts, which Tissues name: a labelUrl beside it would mean other labels.
  if (partLabels_ && !node.labelUrl.get().empty()) {
    sink.error(node.location(), "VolumeObject has a labelUrl and a mesh url: a mesh's parts are its labels; drop the labelUrl");
    return;
  }
  const auto& labelUrls = node.labelUrl.get();
  if (preloaded_ && !labelUrls.empty() && labelUrls.front() == preloadedUrl_) {
    labels = std::move(preloaded_);
  } else if (!labelUrls.empty()) {
    // What is left of reading them, if they were started ahead.
    const ProgressStep step(sink.progress(), name(node) + ": reading its labels" +
                                                 (labelsAhead_.valid() ? std::string() : " " + labelUrls.front()));
    LabelsRead read = labelsAhead_.valid() ? labelsAhead_.get() : readLabels(labelUrls, base);
    labels = std::move(read.labels), failures = std::move(read.failures);
  }
  if (!node.labelUrl.get().empty() && !labels) {
    sink.error(node.location(), "VolumeObject could not load any of its labelUrl volumes:" + failures);
    return;
  }
  // A mesh's own parts label it unless a labelUrl is given.
  if (!labels && partLabels_) labels = std::move(partLabels_);
  // A tissue by name needs a mesh part of its name: said at the tissue.
  bool unnamed = false;
  for (const Tissue* t : list) {
    if (!t->byPartName() || std::find(parts_.begin(), parts_.end(), t->name.get()) != parts_.end()) continue;
    std::string known;
    for (const std::string& p : parts_) known += (known.empty() ? "" : ", ") + ("'" + p + "'");
    sink.error(t->location(), "Tissue '" + t->name.get() + "' has neither densityRange nor label, and " +
                                  (parts_.empty() ? std::string("the volume is not a mesh with parts to choose it by name; give one")
                                                  : "the mesh has no part of that name (its parts: " + known + ")"));
    unnamed = true;
  }
  if (unnamed) return;
  const ProgressStep step(sink.progress(), name(node) + ": classifying its tissues");
  try {
    tissueMap_ = TissueMap::build(volume_, list, labels.get(), isoValue_, parts_);
  } catch (const VolumeError& e) {
    sink.error(node.location(), std::string("VolumeObject tissues: ") + e.what());
    return;
  }
  // A tissue no voxel is made of is almost always a wrong range or label.
  const auto& counts = tissueMap_->voxelCounts();
  for (std::size_t i = 0; i < list.size(); ++i)
    if (counts[i + 1] == 0)
      sink.warning(list[i]->location(), "Tissue '" + list[i]->name.get() + "' matches no voxel of the volume");
}

// Whether url and the first labelUrl name the same phantom's densities and
// labels, which are then made in one pass (they share every distance the
// phantom computes: at 25 µm two passes were 5.2 s of an 11 s `check`). Only
// when Tissues will read the labels. A url that does not parse is left to the
// separate loads, which say what is wrong with it.
std::optional<ToothPhantomOptions> samePhantomBoth(const VolumeObject& node, const std::string& url) {
  const auto& labelUrls = node.labelUrl.get();
  if (node.tissues.get().empty() || labelUrls.empty() || url.rfind("phantom:", 0) != 0 || !isPhantomLabelsUrl(labelUrls.front()))
    return std::nullopt;
  try {
    const ToothPhantomOptions a = parsePhantomUrl(url);
    const ToothPhantomOptions b = parsePhantomLabelsUrl(labelUrls.front());
    if (a.dims == b.dims && a.voxelSize == b.voxelSize && a.socket == b.socket) return a;
  } catch (const VolumeError&) {
  }
  return std::nullopt;
}

}  // namespace

std::unique_ptr<VolumeContents> loadVolumeContents(VolumeObject& node, DiagnosticSink& sink) {
  const std::filesystem::path base = node.location().file.empty()
                                         ? std::filesystem::path()
                                         : std::filesystem::path(node.location().file).parent_path();
  const glm::dvec3 override(node.voxelSize.get());
  // The field's own range is [0, kMaxVoxelSize]: 0 0 0 takes the file's, and
  // a range cannot leave out what lies between 0 and the smallest voxel.
  if (override != glm::dvec3(0.0))
    for (int a = 0; a < 3; ++a)
      if (!(override[a] >= kMinVoxelSize)) {
        sink.error(node.location(), "VolumeObject voxelSize " + formatNumber(node.voxelSize.get()[a]) + " m along " + "xyz"[a] +
                                        " is below the smallest voxel size, " + formatNumber(kMinVoxelSize) +
                                        " m (lengths are metres unless a <unit> statement says otherwise: 0.1 mm is 0.0001; 0 0 0 "
                                        "takes the file's)");
        return nullptr;
      }
  // A mesh is voxelised at voxelSize (cubic), its soft parts below the isoValue.
  MeshVoxelOptions mesh;
  mesh.voxelSize = override.x == override.y && override.y == override.z ? override.x : -1.0;
  mesh.unit = node.meshUnit.get();
  mesh.isoValue = node.isoValue.get(), mesh.airValue = node.airValue.get();
  for (const auto& t : node.tissues.get())
    if (t->soft.get() && t->byPartName()) mesh.softParts.insert(t->name.get());
    else if (t->soft.get() && !t->byDensity()) mesh.softLabels.insert(t->label.get());
  std::string failures;
  std::vector<std::string> failed;
  // Several mesh urls are the parts of one volume (enamel.stl, dentin.stl, pulp.stl), not fallbacks.
  const auto& urls = node.url.get();
  const bool meshParts = urls.size() > 1 && std::all_of(urls.begin(), urls.end(), [](const std::string& u) { return isMeshFile(u); });
  // The labels read on another thread while the densities are (two files, two
  // cores: a 25 µm NRRD and its label NRRD open in 0.77 of the time).
  // Not the phantom's pair, which one pass makes, nor beside a mesh, whose
  // parts are its labels (a labelUrl there is an error).
  std::future<LabelsRead> labelsAhead;
  if (!node.tissues.get().empty() && !node.labelUrl.get().empty() && !urls.empty() && !isMeshFile(urls.front()) &&
      !samePhantomBoth(node, urls.front()))
    try {
      labelsAhead = std::async(std::launch::async, [labelUrls = node.labelUrl.get(), base] { return readLabels(labelUrls, base); });
    } catch (const std::system_error&) {  // no thread to be had: they are read after the densities, as before
    }
  for (const std::string& u : meshParts ? std::vector<std::string>{urls.front()} : urls) {
    try {
      if (mesh.voxelSize < 0.0 && isMeshFile(u))
        throw VolumeError(u + ": a mesh is voxelised in cubic voxels; give voxelSize the same along x, y and z (it is " +
                          node.voxelSize.toString() + ")");
      std::optional<VoxelVolume> phantomLabels;
      const std::optional<ToothPhantomOptions> both = meshParts ? std::nullopt : samePhantomBoth(node, u);
      LoadedVolume loaded = [&] {
        const ProgressStep step(sink.progress(), name(node) + ": reading " + (both ? "the densities and labels of " : "") +
                                                     (meshParts ? "its mesh parts" : u));
        if (meshParts) return loadMeshParts(urls, base, mesh);
        if (both) {
          ToothPhantomWithLabels made = makeToothPhantomWithLabels(*both);
          phantomLabels.emplace(std::move(made.labels));
          return LoadedVolume{std::move(made.densities), "phantom", u};
        }
        return loadVolume(u, base, node.airValue.get(), &mesh, override);
      }();
      const bool isMesh = loaded.labels.has_value();
      auto contents = std::make_unique<VoxelContents>(
          override != glm::dvec3(0.0) && !isMesh
              ? VoxelVolume(loaded.volume.gridPtr(), loaded.volume.dims(), override, node.airValue.get())
              : std::move(loaded.volume),
          loaded.format, node.isoValue.get());
      if (phantomLabels) contents->setPreloadedLabels(node.labelUrl.get().front(), std::move(*phantomLabels));
      if (labelsAhead.valid()) contents->setLabelsAhead(std::move(labelsAhead));
      if (isMesh) {
        contents->setParts(std::move(*loaded.labels), loaded.parts);
        sink.note(node.location(), "VolumeObject " + u + ": " + loaded.account);
      }
      node.loadedUrl.set(meshParts ? loaded.source : u);
      // A fallback url loaded: say why each earlier one did not.
      for (const std::string& f : failed)
        sink.note(node.location(), "VolumeObject url failed, a later one was used: " + f);
      // A volume with nothing above isoValue is felt, milled and drawn as
      // nothing: almost always the wrong isoValue, units or voxel size.
      // Stops at the first voxel with material: a whole scan only for the volume that has none.
      float densest = -std::numeric_limits<float>::infinity();
      const float iso = node.isoValue.get();
      for (auto it = contents->voxels().grid().cbeginValueOn(); it && !(densest > iso); ++it)
        densest = std::max(densest, *it);
      if (!(densest > iso))
        sink.error(node.location(), "VolumeObject " + u + " holds no material: no voxel is above isoValue " +
                                        formatNumber(iso) +
                                        (std::isfinite(densest) ? " (the densest is " + formatNumber(densest) + ")"
                                                                : std::string(" (every voxel is air)")) +
                                        "; check isoValue, the data's units or the voxel size");
      contents->classifyTissues(node, base, sink);
      return contents;
    } catch (const VolumeError& e) {
      failed.emplace_back(e.what());
      failures += "\n  " + failed.back();
    } catch (const std::bad_alloc&) {
      // A header that declares more voxels than memory holds: an error for this url, not a crash.
      failed.push_back(u + ": out of memory while reading the volume (" +
                       (u.rfind("phantom:", 0) == 0 ? std::string("the phantom at this size needs more memory than there is")
                                                    : std::string("its header declares more data than fits")) +
                       ")");
      failures += "\n  " + failed.back();
    }
  }
  sink.error(node.location(), "VolumeObject could not load any of its urls:" + failures);
  return nullptr;
}

namespace {

const VolumeModule kModule{kVolumeAbiVersion, &loadVolumeContents, &checkLessonVolumes};

}  // namespace

}  // namespace millsim

// Typed as the loader calls it (SiblingLibrary: const void* (*)()): a call through
// another function type is undefined behaviour (clang's -fsanitize=function).
extern "C" __attribute__((visibility("default"))) const void* millsim_volume_module() {
  return &millsim::kModule;
}
