// The medical-image readers load lazily (issue 15): VTK and GDCM are in
// libmillsim_medical, which libmillsim opens only when a volume needs it. This
// suite is its own executable, linked with neither (tests/CMakeLists.txt), and
// reads what the process has mapped from /proc/self/maps: a scene whose volume
// is a .vdb, a .nrrd or the phantom maps neither VTK nor GDCM, and a .vti scene
// in the same process still reads, mapping them then.
#include <gtest/gtest.h>

#include <fstream>
#include <memory>
#include <set>
#include <sstream>
#include <string>

#include "millsim/core/NodeRegistry.h"
#include "millsim/volume/ToothPhantom.h"
#include "millsim/volume/VolumeIO.h"
#include "millsim/volume/VolumeObject.h"
#include "millsim/volume/VoxelVolume.h"
#include "millsim/x3d/X3DLoader.h"
#include "TestFiles.h"

using namespace millsim;
using millsim::test::ScratchDir;
using millsim::test::x3d;
namespace fs = std::filesystem;

namespace {

// The file names of every shared object the process has mapped.
std::set<std::string> mappedLibraries() {
  std::set<std::string> names;
  std::ifstream maps("/proc/self/maps");
  std::string line;
  while (std::getline(maps, line)) {
    const auto slash = line.find('/');
    if (slash == std::string::npos) continue;
    const std::string name = fs::path(line.substr(slash)).filename().string();
    if (name.find(".so") != std::string::npos) names.insert(name);
  }
  return names;
}

// The mapped libraries whose name starts with one of VTK's, GDCM's or libmillsim_medical's.
std::string medicalLibrariesMapped() {
  std::string found;
  for (const std::string& name : mappedLibraries())
    if (name.rfind("libvtk", 0) == 0 || name.rfind("libgdcm", 0) == 0 || name.rfind("libmillsim_medical", 0) == 0)
      found += name + " ";
  return found;
}

// Loads the scene and returns the size of its VolumeObject "V" in voxels.
glm::ivec3 loadedDims(const fs::path& scene) {
  const LoadResult result = loadSceneFile(scene, builtinRegistry());
  EXPECT_TRUE(result.ok()) << result.report();
  if (!result.ok()) return glm::ivec3(0);
  auto* volume = dynamic_cast<VolumeObject*>(result.scene->def("V").get());
  EXPECT_NE(volume, nullptr);
  return volume && volume->volume() ? volume->volume()->dims() : glm::ivec3(0);
}

std::string volumeScene(const std::string& url) {
  return x3d("<VolumeObject DEF=\"V\" url='\"" + url + "\"' isoValue=\"700\"/>");
}

}  // namespace

// One test, in this order, so that no other test of the process can load the
// library first.
TEST(LazyReaders, VdbNrrdAndPhantomScenesMapNoVtkOrGdcmAndAVtiSceneStillReads) {
  ASSERT_EQ(medicalLibrariesMapped(), "") << "mapped before any volume was read";
  bool openvdb = false;  // which libmillsim links: proves the check sees the process's libraries
  for (const std::string& name : mappedLibraries()) openvdb = openvdb || name.rfind("libopenvdb", 0) == 0;
  ASSERT_TRUE(openvdb) << "libopenvdb is not among the mapped libraries: the check cannot see them";

  ScratchDir dir;
  ToothPhantomOptions small;
  small.dims = glm::ivec3(24, 24, 16);
  const VoxelVolume tooth = makeToothPhantom(small);
  writeVdb(tooth, dir.path() / "tooth.vdb");
  writeNrrd(tooth, dir.path() / "tooth.nrrd");

  EXPECT_EQ(loadedDims(dir.write("vdb.x3d", volumeScene("tooth.vdb"))), small.dims);
  EXPECT_EQ(medicalLibrariesMapped(), "") << "after a .vdb scene";
  EXPECT_EQ(loadedDims(dir.write("nrrd.x3d", volumeScene("tooth.nrrd"))), small.dims);
  EXPECT_EQ(medicalLibrariesMapped(), "") << "after a .nrrd scene";
  EXPECT_EQ(loadedDims(dir.write("phantom.x3d", volumeScene("phantom:tooth?size=24,24,16"))), small.dims);
  EXPECT_EQ(medicalLibrariesMapped(), "") << "after a phantom scene";

  // A VTK XML image, 3 x 2 x 2 voxels of bone in air, written by hand.
  dir.write("small.vti",
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
            "<ImageData WholeExtent=\"0 2 0 1 0 1\" Origin=\"0 0 0\" Spacing=\"0.5 0.5 0.5\">\n"
            "<Piece Extent=\"0 2 0 1 0 1\">\n<PointData Scalars=\"density\">\n"
            "<DataArray type=\"Int16\" Name=\"density\" NumberOfComponents=\"1\" format=\"ascii\">\n"
            "-1000 900 -1000 900 900 900 -1000 900 -1000 900 900 900\n"
            "</DataArray>\n</PointData>\n<CellData/>\n</Piece>\n</ImageData>\n</VTKFile>\n");
  EXPECT_EQ(loadedDims(dir.write("vti.x3d", volumeScene("small.vti"))), glm::ivec3(3, 2, 2));
  const std::string mapped = medicalLibrariesMapped();
  EXPECT_NE(mapped.find("libmillsim_medical"), std::string::npos) << mapped;
  EXPECT_NE(mapped.find("libvtkIOXML"), std::string::npos) << mapped;
  EXPECT_NE(mapped.find("libgdcmMSFF"), std::string::npos) << mapped;
}
