#include "measure/Resolution.h"

#include <charconv>
#include <chrono>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "millsim/core/NodeRegistry.h"
#include "millsim/volume/ToothPhantom.h"
#include "millsim/volume/VolumeObject.h"
#include "millsim/volume/VoxelVolume.h"

namespace millsim::measure {

namespace {

std::string shortest(double v) {  // the shortest text that reads back as v
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return ec == std::errc() ? std::string(buf, end) : std::to_string(v);
}

VolumeObject* firstVolume(const Scene& scene, const std::string& scenePath) {
  const auto volumes = scene.nodesOfType<VolumeObject>();
  if (volumes.empty()) throw std::runtime_error(scenePath + ": no VolumeObject to resample");
  return volumes.front();
}

}  // namespace

std::vector<LoadOptions::FieldOverride> phantomAtVoxelSize(const std::string& scenePath, double h, glm::ivec3* dims) {
  if (!(h >= kMinVoxelSize && h <= kMaxVoxelSize))
    throw std::runtime_error("voxel size " + shortest(h) + " m is outside [" + shortest(kMinVoxelSize) + ", " +
                             shortest(kMaxVoxelSize) + "] m");
  LoadResult loaded = loadSceneFile(scenePath, builtinRegistry());
  if (!loaded.ok()) throw std::runtime_error(loaded.report());
  const VolumeObject& volume = *firstVolume(*loaded.scene, scenePath);
  const std::string url = volume.url.get().empty() ? std::string() : volume.url.get().front();
  if (url.rfind("phantom:tooth", 0) != 0 || isPhantomLabelsUrl(url))
    throw std::runtime_error(scenePath + ": its VolumeObject reads '" + url +
                             "'; the resolution bench resamples the tooth phantom (url 'phantom:tooth...')");
  const ToothPhantomOptions o = parsePhantomUrl(url);
  const glm::dvec3 extent = glm::dvec3(o.dims) * o.voxelSize;
  const glm::ivec3 n(glm::round(extent / h));
  if (dims) *dims = n;
  const std::string options = "?size=" + std::to_string(n.x) + "," + std::to_string(n.y) + "," + std::to_string(n.z) +
                              "&voxel=" + shortest(h) + "&socket=" + (o.socket ? "1" : "0");
  std::vector<LoadOptions::FieldOverride> set{{"VolumeObject", "url", "\"phantom:tooth" + options + "\""}};
  const auto& labels = volume.labelUrl.get();
  if (!labels.empty() && isPhantomLabelsUrl(labels.front()))
    set.push_back({"VolumeObject", "labelUrl", "\"phantom:tooth-labels" + options + "\""});
  return set;
}

ResolutionLoad measureLoad(const std::string& scenePath, double h) {
  ResolutionLoad r;
  r.voxelSize = h;
  r.overrides = phantomAtVoxelSize(scenePath, h, &r.dims);
  LoadOptions options;
  options.overrides = r.overrides;
  const bool reset = resetPeakResident();
  const auto t0 = std::chrono::steady_clock::now();
  LoadResult loaded = loadSceneFile(scenePath, builtinRegistry(), options);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.peakMiB = reset ? peakResidentMiB() : -1.0;
  if (!loaded.ok()) throw std::runtime_error(loaded.report());
  if (const VoxelVolume* v = firstVolume(*loaded.scene, scenePath)->volume()) r.materialVoxels = v->activeVoxels();
  return r;
}

double peakResidentMiB() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;  // "VmHWM:  123456 kB"
  return -1.0;
}

bool resetPeakResident() {
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";  // 5: reset the peak resident size (Linux 4.0)
  clear.flush();
  return bool(clear);
}

}  // namespace millsim::measure
