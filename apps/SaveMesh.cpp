#include "SaveMesh.h"

#include <cctype>
#include <cstdio>
#include <stdexcept>

#include "ImageArgs.h"
#include "millsim/volume/SurfaceExport.h"
#include "millsim/volume/VolumeObject.h"

namespace millsim::app {

void checkSaveMesh(const Scene& scene, const std::filesystem::path& file) {
  if (!isMeshOutput(file))
    throw std::invalid_argument("--save-mesh " + file.string() +
                                ": the milled surface is written as .stl (the whole), .obj or .ply (a solid per tissue)");
  const std::size_t n = scene.nodesOfType<VolumeObject>().size();
  if (n != 1)
    throw std::invalid_argument("--save-mesh writes one volume's surface; the scene has " + std::to_string(n) +
                                " VolumeObjects");
  checkWritable(file, "--save-mesh");
  std::string extension = file.extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (extension == ".obj") {  // and its colours beside it
    std::filesystem::path mtl = file;
    checkWritable(mtl.replace_extension(".mtl"), "--save-mesh");
  }
}

std::string saveMesh(const Scene& scene, const std::filesystem::path& file) {
  for (const VolumeObject* v : scene.nodesOfType<VolumeObject>())
    if (v->volume()) {
      const std::vector<SolidSurface> solids =
          extractSolids(*v->volume(), v->isoValue.get(), v->tissueMap(), splitFor(file));
      writeSolids(solids, file);
      std::string names;
      for (const SolidSurface& s : solids) names += (names.empty() ? "" : ", ") + s.name;
      char line[160];
      std::snprintf(line, sizeof line, "%zu triangles in millimetres", triangleCount(solids));
      return "  milled surface written to " + file.string() + ": " + line +
             (solids.empty() ? "; no material is left" : "; " + std::string(solids.size() == 1 ? "solid " : "solids ") + names) +
             "\n";
    }
  throw std::runtime_error("--save-mesh: the scene's VolumeObject holds no volume");
}

}  // namespace millsim::app
