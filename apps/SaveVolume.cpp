#include "SaveVolume.h"

#include <stdexcept>

#include "ImageArgs.h"
#include "millsim/volume/VolumeIO.h"
#include "millsim/volume/VolumeObject.h"

namespace millsim::app {

void checkOneVolume(const Scene& scene, const std::string& flag, const std::string& what) {
  const std::size_t n = scene.nodesOfType<VolumeObject>().size();
  if (n != 1)
    throw std::invalid_argument(flag + " writes " + what + "; the scene has " + std::to_string(n) + " VolumeObjects");
}

const VolumeObject& theSavedVolume(const Scene& scene, const std::string& flag) {
  for (const VolumeObject* v : scene.nodesOfType<VolumeObject>())
    if (v->volume()) return *v;
  throw std::runtime_error(flag + ": the scene's VolumeObject holds no volume");
}

void checkSaveVolume(const Scene& scene, const std::filesystem::path& file) {
  if (file.extension() != ".vdb")
    throw std::invalid_argument("--save-volume " + file.string() +
                                ": the milled volume is written as OpenVDB; name the file .vdb");
  checkOneVolume(scene, "--save-volume", "one volume");
  checkWritable(file, "--save-volume");
}

std::string saveVolume(const Scene& scene, const std::filesystem::path& file) {
  writeVdb(*theSavedVolume(scene, "--save-volume").volume(), file);
  return "  milled volume written to " + file.string() + "\n";
}

}  // namespace millsim::app
