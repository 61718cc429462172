#include "SaveMesh.h"

#include <cctype>
#include <stdexcept>

#include "ImageArgs.h"
#include "SaveVolume.h"
#include "millsim/volume/SurfaceExport.h"
#include "millsim/volume/VolumeObject.h"

namespace millsim::app {

void checkSaveMesh(const Scene& scene, const std::filesystem::path& file) {
  if (!isMeshOutput(file))
    throw std::invalid_argument("--save-mesh " + file.string() +
                                ": the milled surface is written as .stl (the whole), .obj or .ply (a solid per tissue)");
  checkOneVolume(scene, "--save-mesh", "one volume's surface");
  checkWritable(file, "--save-mesh");
  std::string extension = file.extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (extension == ".obj") {  // and its colours beside it
    std::filesystem::path mtl = file;
    checkWritable(mtl.replace_extension(".mtl"), "--save-mesh");
  }
}

std::string saveMesh(const Scene& scene, const std::filesystem::path& file) {
  const VolumeObject& v = theSavedVolume(scene, "--save-mesh");
  const std::vector<SolidSurface> solids = extractSolids(*v.volume(), v.isoValue.get(), v.tissueMap(), splitFor(file));
  writeSolids(solids, file);
  std::string names;
  for (const SolidSurface& s : solids) names += (names.empty() ? "" : ", ") + s.name;
  return "  milled surface written to " + file.string() + ": " + std::to_string(triangleCount(solids)) +
         " triangles in millimetres" +
         (solids.empty() ? "; no material is left" : "; " + std::string(solids.size() == 1 ? "solid " : "solids ") + names) +
         "\n";
}

}  // namespace millsim::app
