#include "SaveVolume.h"

#include <stdexcept>

#include "ImageArgs.h"
#include "millsim/volume/VolumeIO.h"
#include "millsim/volume/VolumeObject.h"

namespace millsim::app {

void checkSaveVolume(const Scene& scene, const std::filesystem::path& file) {
  if (file.extension() != ".vdb")
    throw std::invalid_argument("--save-volume " + file.string() +
                                ": the milled volume is written as OpenVDB; name the file .vdb");
  const std::size_t n = scene.nodesOfType<VolumeObject>().size();
  if (n != 1)
    throw std::invalid_argument("--save-volume writes one volume; the scene has " + std::to_string(n) +
                                " VolumeObjects");
  checkWritable(file, "--save-volume");
}

std::string saveVolume(const Scene& scene, const std::filesystem::path& file) {
  for (const VolumeObject* v : scene.nodesOfType<VolumeObject>())
    if (v->volume()) {
      writeVdb(*v->volume(), file);
      return "  milled volume written to " + file.string() + "\n";
    }
  throw std::runtime_error("--save-volume: the scene's VolumeObject holds no volume");
}

}  // namespace millsim::app
