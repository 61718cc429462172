// Surface meshes as volumes (MeshFile, MeshVolume; issue 45): STL (ASCII and
// binary), OBJ and PLY read into closed parts and voxelised with the volume
// the surface encloses; nested parts labelled innermost first; open parts,
// hostile files and a wrong unit refused with the reason; a scene's Tissues
// choose parts by name. Every mesh is written here by an independent writer.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <numbers>

#include "TestFiles.h"
#include "millsim/core/NodeRegistry.h"
#include "millsim/volume/MeshFile.h"
#include "millsim/volume/MeshVolume.h"
#include "millsim/volume/TissueMap.h"
#include "millsim/volume/VolumeError.h"
#include "millsim/volume/VolumeIO.h"
#include "millsim/volume/VolumeObject.h"
#include "millsim/x3d/X3DLoader.h"

using namespace millsim;
using namespace millsim::test;
namespace fs = std::filesystem;

namespace {

struct TestMesh {
  std::vector<glm::dvec3> v;
  std::vector<glm::uvec3> f;  // counter-clockwise seen from outside
};

TestMesh box(glm::dvec3 lo, glm::dvec3 hi) {
  TestMesh m;
  for (int c = 0; c < 8; ++c) m.v.push_back({c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z});
  const unsigned quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) m.f.push_back({q[0], q[1], q[2]}), m.f.push_back({q[0], q[2], q[3]});
  return m;
}

// An icosahedron subdivided `levels` times onto a sphere.
TestMesh sphere(double r, int levels, glm::dvec3 centre = glm::dvec3(0.0)) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  TestMesh m;
  for (glm::dvec3 p : {glm::dvec3(-1, t, 0), {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t}, {0, -1, -t},
                       {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}})
    m.v.push_back(glm::normalize(p));
  m.f = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
         {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8}, {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<unsigned, unsigned>, unsigned> mid;
    auto middle = [&](unsigned a, unsigned b) {
      const auto key = std::minmax(a, b);
      if (auto it = mid.find(key); it != mid.end()) return it->second;
      m.v.push_back(glm::normalize(m.v[a] + m.v[b]));
      return mid[key] = unsigned(m.v.size() - 1);
    };
    std::vector<glm::uvec3> next;
    for (const glm::uvec3& f : m.f) {
      const unsigned ab = middle(f.x, f.y), bc = middle(f.y, f.z), ca = middle(f.z, f.x);
      next.insert(next.end(), {{f.x, ab, ca}, {f.y, bc, ab}, {f.z, ca, bc}, {ab, bc, ca}});
    }
    m.f = next;
  }
  for (glm::dvec3& p : m.v) p = centre + r * p;
  return m;
}

double volumeOf(const TestMesh& m) {
  double v = 0.0;
  for (const glm::uvec3& f : m.f) v += glm::dot(m.v[f.x], glm::cross(m.v[f.y], m.v[f.z]));
  return v / 6.0;
}

std::string asciiStl(const std::vector<std::pair<std::string, TestMesh>>& solids) {
  std::string s;
  char line[200];
  for (const auto& [name, m] : solids) {
    s += "solid " + name + "\n";
    for (const glm::uvec3& f : m.f) {
      s += "  facet normal 0 0 0\n    outer loop\n";
      for (int k = 0; k < 3; ++k) {
        const glm::dvec3& p = m.v[f[k]];
        std::snprintf(line, sizeof line, "      vertex %.9g %.9g %.9g\n", p.x, p.y, p.z);
        s += line;
      }
      s += "    endloop\n  endfacet\n";
    }
    s += "endsolid " + name + "\n";
  }
  return s;
}

template <class T> void put(std::string& s, T v, bool big = false) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big) std::reverse(b, b + sizeof(T));
  s.append(b, sizeof(T));
}

std::string binaryStl(const TestMesh& m) {
  std::string s(80, ' ');
  s.replace(0, 11, "binary mesh");
  put(s, std::uint32_t(m.f.size()));
  for (const glm::uvec3& f : m.f) {
    for (int k = 0; k < 3; ++k) put(s, 0.f);
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) put(s, float(m.v[f[k]][a]));
    put(s, std::uint16_t(0));
  }
  return s;
}

std::string obj(const std::vector<std::pair<std::string, TestMesh>>& groups) {
  std::string s = "# written by MeshVolumeTest\n";
  unsigned base = 0;
  char line[200];
  for (const auto& [name, m] : groups) {
    s += "g " + name + "\n";
    for (const glm::dvec3& p : m.v) {
      std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", p.x, p.y, p.z);
      s += line;
    }
    for (const glm::uvec3& f : m.f)
      s += "f " + std::to_string(base + f.x + 1) + "//1 " + std::to_string(base + f.y + 1) + " " +
           std::to_string(base + f.z + 1) + "/1\n";
    base += unsigned(m.v.size());
  }
  return s;
}

std::string ply(const TestMesh& m, const std::string& format) {
  std::string s = "ply\nformat " + format + " 1.0\ncomment MeshVolumeTest\nelement vertex " + std::to_string(m.v.size()) +
                  "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nelement face " +
                  std::to_string(m.f.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  const bool big = format == "binary_big_endian";
  for (const glm::dvec3& p : m.v) {
    if (format == "ascii") {
      char line[200];
      std::snprintf(line, sizeof line, "%.9g %.9g %.9g 200\n", p.x, p.y, p.z);
      s += line;
    } else {
      for (int a = 0; a < 3; ++a) put(s, float(p[a]), big);
      put(s, std::uint8_t(200));
    }
  }
  for (const glm::uvec3& f : m.f) {
    if (format == "ascii") {
      s += "3 " + std::to_string(f.x) + " " + std::to_string(f.y) + " " + std::to_string(f.z) + "\n";
    } else {
      put(s, std::uint8_t(3));
      for (int k = 0; k < 3; ++k) put(s, std::int32_t(f[k]), big);
    }
  }
  return s;
}

std::filesystem::path writeFile(const ScratchDir& dir, const std::string& name, const std::string& bytes) {
  const auto p = dir.path() / name;
  std::ofstream(p, std::ios::binary) << bytes;
  return p;
}

MeshVoxelOptions inMillimetres(double voxelMm) {
  MeshVoxelOptions o;
  o.voxelSize = voxelMm * 1e-3;
  o.unit = 1e-3;
  return o;
}

// What milling counts as material: Σ φ·h³ (φ ½ at the isoValue).
double materialVolume(const VoxelVolume& v, const MeshVoxelOptions& o) {
  const double h = v.voxelSize().x, scale = 1.0 / (2.0 * (double(o.isoValue) - o.airValue));
  double sum = 0.0;
  for (auto it = v.grid().cbeginValueOn(); it; ++it) sum += std::clamp((double(*it) - o.airValue) * scale, 0.0, 1.0);
  return sum * h * h * h;
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const VolumeError& e) {
    return e.what();
  }
  return "(no error)";
}

// ---- Readers and the enclosed volume ----

class MeshFormats : public ::testing::TestWithParam<std::string> {};

// A 2 × 3 × 4 mm box in each format holds 24 mm³ within 1 % at 0.05 mm voxels.
TEST_P(MeshFormats, ABoxHoldsItsVolume) {
  ScratchDir dir;
  const TestMesh m = box({-1.0, -1.5, -2.0}, {1.0, 1.5, 2.0});
  const std::string f = GetParam();
  const auto file = f == "stl" ? writeFile(dir, "box.stl", asciiStl({{"box", m}}))
                    : f == "binary-stl" ? writeFile(dir, "box.stl", binaryStl(m))
                    : f == "obj" ? writeFile(dir, "box.obj", obj({{"box", m}}))
                                 : writeFile(dir, "box.ply", ply(m, f));
  const SurfaceMesh mesh = readSurfaceMesh(file);
  ASSERT_EQ(mesh.parts.size(), 1u);
  EXPECT_EQ(mesh.parts[0].name, "box");
  EXPECT_EQ(mesh.parts[0].vertices.size(), 8u) << "corners at one position are one vertex";
  EXPECT_EQ(mesh.parts[0].triangles.size(), 12u);
  EXPECT_EQ(openEdges(mesh.parts[0]).count, 0u);
  EXPECT_NEAR(enclosedVolume(mesh.parts[0]), 24.0, 1e-4);
  const MeshVoxelOptions o = inMillimetres(0.05);
  const MeshVolume v = voxeliseMesh(mesh, file.string(), o);
  EXPECT_NEAR(materialVolume(v.density, o) * 1e9, 24.0, 0.24);
  EXPECT_NEAR(v.size.x, 2e-3, 1e-9);
  EXPECT_NEAR(v.size.z, 4e-3, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(MeshVolume, MeshFormats,
                         ::testing::Values("stl", "binary-stl", "obj", "ascii", "binary_little_endian", "binary_big_endian"),
                         [](const auto& p) {
                           std::string n = p.param;
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n;
                         });

// A sphere of 2 mm radius (5120 triangles) holds what its surface encloses within 1 %.
TEST(MeshVolume, ASphereHoldsWhatItsSurfaceEncloses) {
  ScratchDir dir;
  const TestMesh m = sphere(2.0, 4);
  const auto file = writeFile(dir, "ball.stl", binaryStl(m));
  const MeshVoxelOptions o = inMillimetres(0.05);
  const MeshVolume v = loadMeshVolume(file, o);
  const double enclosed = volumeOf(m);
  EXPECT_NEAR(enclosed, 4.0 / 3.0 * std::numbers::pi * 8.0, 0.02 * 33.5);
  EXPECT_NEAR(materialVolume(v.density, o) * 1e9, enclosed, 0.01 * enclosed);
  EXPECT_NEAR(v.enclosed[0] * 1e9, enclosed, 1e-3);
}

// Three nested spheres, one OBJ group each: every voxel takes the innermost
// part's label, and each label's voxels hold its shell within 2 %.
TEST(MeshVolume, NestedPartsTakeTheInnermostLabel) {
  ScratchDir dir;
  const TestMesh enamel = sphere(3.0, 4), dentin = sphere(2.0, 4), pulp = sphere(1.2, 4, {0.2, 0.1, 0.0});
  const auto file = writeFile(dir, "tooth.obj", obj({{"enamel", enamel}, {"dentin", dentin}, {"pulp", pulp}}));
  const MeshVoxelOptions o = inMillimetres(0.05);
  const MeshVolume v = loadMeshVolume(file, o);
  ASSERT_EQ(v.parts, (std::vector<std::string>{"enamel", "dentin", "pulp"}));
  std::map<int, double> counted;
  auto labels = v.labels.grid().getConstAccessor();
  const double h3 = std::pow(0.05, 3);
  for (auto it = v.density.grid().cbeginValueOn(); it; ++it)
    if (*it >= o.isoValue) counted[int(std::lround(labels.getValue(it.getCoord())))] += h3;
  const double shells[3] = {volumeOf(enamel) - volumeOf(dentin), volumeOf(dentin) - volumeOf(pulp), volumeOf(pulp)};
  for (int l = 1; l <= 3; ++l)
    EXPECT_NEAR(counted[l], shells[l - 1], 0.02 * shells[l - 1]) << v.parts[std::size_t(l - 1)];
  EXPECT_EQ(counted.count(0), 0u) << "every material voxel has a label";
}

// A soft part (the pulp) lies below the isoValue: the burr does not feel it.
TEST(MeshVolume, ASoftPartLiesBelowTheIsoValue) {
  ScratchDir dir;
  const auto file = writeFile(dir, "tooth.obj", obj({{"dentin", sphere(2.0, 3)}, {"pulp", sphere(1.0, 3)}}));
  MeshVoxelOptions o = inMillimetres(0.1);
  o.softParts = {"pulp"};
  const MeshVolume v = loadMeshVolume(file, o);
  const glm::ivec3 centre = v.density.dims() / 2;
  EXPECT_LT(v.density.valueAt(centre.x, centre.y, centre.z), o.isoValue) << "the pulp's centre";
  EXPECT_GT(v.density.valueAt(centre.x + 15, centre.y, centre.z), o.isoValue) << "dentin 1.5 mm out";
  EXPECT_EQ(v.labels.valueAt(centre.x, centre.y, centre.z), 2.f);
}

// ---- What is refused ----

TEST(MeshVolume, AnOpenPartIsNamedWithItsOpenEdges) {
  ScratchDir dir;
  TestMesh lid = box({0, 0, 0}, {2, 3, 4});
  lid.f.erase(lid.f.begin() + 2, lid.f.begin() + 4);  // the top face (z = 4): a lidless box
  const auto file = writeFile(dir, "parts.stl", asciiStl({{"base", box({-5, -5, -5}, {-3, -3, -3})}, {"lid", lid}}));
  const std::string e = errorOf([&] { loadMeshVolume(file, inMillimetres(0.1)); });
  EXPECT_NE(e.find("parts.stl: part 'lid' is not closed: 4 open edges"), std::string::npos) << e;
  EXPECT_NE(e.find("the widest hole 2.4 mm across"), std::string::npos) << e;  // 4 × 6 mm² / 10 mm
}

// 1001 groups of one triangle each: more parts than MillSim voxelises.
std::string manyGroups() {
  std::string s = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  for (int g = 0; g <= 1000; ++g) s += "g part" + std::to_string(g) + "\nf 1 2 3\n";
  return s;
}

TEST(MeshVolume, HostileFilesAreRefusedWithTheReason) {
  ScratchDir dir;
  struct Case {
    std::string name, bytes, phrase;
  };
  std::string claims = std::string(80, 'x');
  put(claims, std::uint32_t(2'000'000'000));
  claims += std::string(100, '\0');
  const std::vector<Case> cases = {
      {"claims.stl", claims, "neither ASCII STL"},
      {"nan.obj", "v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n", "nan.obj:2: coordinate 'nan' is not a finite number"},
      {"far.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "far.obj:4: face vertex 4 is out of range (the file has 3 vertices)"},
      {"quad.stl", "solid q\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\n",
       "quad.stl:7: a facet with more than three vertices"},
      {"huge.ply", "ply\nformat ascii 1.0\nelement vertex 900000000\nproperty float x\nproperty float y\nproperty float z\n"
                   "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n",
       "huge.ply: 900000000 vertex elements, too many to voxelise"},
      {"endless.ply", "ply\nformat ascii 1.0\n" + std::string(2 << 20, ' '), "line 3 of the PLY header is longer than 1048576 bytes"},
      {"empty.obj", "# nothing\n", "empty.obj: no faces"},
      {"floatindex.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                         "element face 1\nproperty list uchar float vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
       "floatindex.ply: the PLY face list 'vertex_indices' holds floating-point values"},
      {"badline.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 x\n0 1 0\n3 0 1 2\n",
       "badline.ply:11: value 'x' is not a number"},
      {"groups.obj", manyGroups(), "more than 1000 groups"},
  };
  for (const Case& c : cases) {
    const auto file = writeFile(dir, c.name, c.bytes);
    const std::string e = errorOf([&] { loadMeshVolume(file, inMillimetres(0.1)); });
    EXPECT_NE(e.find(c.phrase), std::string::npos) << c.name << ": " << e;
    EXPECT_EQ(e.rfind(file.string(), 0), 0u) << "the message begins with the file: " << e;
  }
}

// A tooth written in millimetres and read in metres is 11 m wide: refused
// before anything is allocated, saying so.
TEST(MeshVolume, AWrongUnitIsRefusedBeforeAllocating) {
  ScratchDir dir;
  const auto file = writeFile(dir, "molar.stl", binaryStl(box({0, 0, 0}, {11, 21, 10})));
  MeshVoxelOptions o;
  o.voxelSize = 50e-6;  // unit 1 m
  const std::string e = errorOf([&] { loadMeshVolume(file, o); });
  EXPECT_NE(e.find("is the file in millimetres? meshUnit='0.001'"), std::string::npos) << e;
}

// ---- In a scene ----

const char* kToothObj = R"(<VolumeObject DEF="Tooth" url='"tooth.obj"' voxelSize="0.0001 0.0001 0.0001" meshUnit="0.001">
  <Tissue name="enamel" hardness="5" color="0.95 0.95 0.92"/>
  <Tissue name="dentin"/>
  <Tissue name="pulp" soft="true" color="0.8 0.3 0.3"/>
</VolumeObject>)";

TEST(MeshVolumeScene, TissuesChooseThePartsByName) {
  ScratchDir dir;
  writeFile(dir, "tooth.obj", obj({{"enamel", sphere(3.0, 3)}, {"dentin", sphere(2.0, 3)}, {"pulp", sphere(1.0, 3)}}));
  LoadResult r = loadSceneFile(dir.write("tooth.x3d", x3d(kToothObj)), builtinRegistry());
  ASSERT_TRUE(r.ok()) << r.report();
  EXPECT_NE(r.report().find("tooth.obj: OBJ, 3 parts ('enamel' 1280 triangles, 'dentin' 1280 triangles, 'pulp' 1280 triangles)"),
            std::string::npos)
      << r.report();
  const auto* volume = dynamic_cast<const VolumeObject*>(r.scene->def("Tooth").get());
  ASSERT_NE(volume, nullptr);
  const TissueMap* tissues = volume->tissueMap();
  ASSERT_NE(tissues, nullptr);
  for (int e = 1; e <= 3; ++e) EXPECT_GT(tissues->voxelCounts()[std::size_t(e)], 1000u) << e;
  EXPECT_EQ(tissues->voxelCounts()[0], 0u) << "no material is left unclassified";
  EXPECT_TRUE(tissues->soft(3));
  EXPECT_FALSE(tissues->soft(2));
}

// Several mesh urls are the parts of one volume, each named by its file.
TEST(MeshVolumeScene, SeveralMeshUrlsAreThePartsOfOneVolume) {
  ScratchDir dir;
  writeFile(dir, "enamel.stl", binaryStl(sphere(3.0, 3)));
  writeFile(dir, "pulp.stl", binaryStl(sphere(1.0, 3)));
  LoadResult r = loadSceneFile(dir.write("two.x3d", x3d(R"(
    <VolumeObject DEF="Tooth" url='"enamel.stl" "pulp.stl"' voxelSize="0.0001 0.0001 0.0001" meshUnit="0.001">
      <Tissue name="enamel"/><Tissue name="pulp" soft="true"/>
    </VolumeObject>)")),
                               builtinRegistry());
  ASSERT_TRUE(r.ok()) << r.report();
  const auto* volume = dynamic_cast<const VolumeObject*>(r.scene->def("Tooth").get());
  ASSERT_NE(volume, nullptr);
  EXPECT_EQ(volume->loadedUrl.get(), "enamel.stl + pulp.stl");
  const TissueMap* tissues = volume->tissueMap();
  ASSERT_NE(tissues, nullptr);
  EXPECT_GT(tissues->voxelCounts()[1], 10000u) << "enamel";
  EXPECT_GT(tissues->voxelCounts()[2], 1000u) << "pulp";
  EXPECT_TRUE(tissues->soft(2));

  fs::create_directories(dir.path() / "other");
  writeFile(dir, "other/enamel.stl", binaryStl(sphere(2.0, 2)));
  LoadResult twice = loadSceneFile(dir.write("twice.x3d", x3d(R"(
    <VolumeObject url='"enamel.stl" "other/enamel.stl"' voxelSize="0.0001 0.0001 0.0001" meshUnit="0.001"/>)")),
                                   builtinRegistry());
  EXPECT_NE(twice.report().find("other/enamel.stl: part 'enamel' is a part of"), std::string::npos) << twice.report();
}

TEST(MeshVolumeScene, MistakesAreClearErrors) {
  ScratchDir dir;
  writeFile(dir, "tooth.obj", obj({{"enamel", sphere(3.0, 2)}, {"dentin", sphere(2.0, 2)}, {"pulp", sphere(1.0, 2)}}));
  auto errorIn = [&](const std::string& body) {
    LoadResult r = loadSceneFile(dir.write("s.x3d", x3d(body)), builtinRegistry());
    return r.report();
  };
  EXPECT_NE(errorIn(R"(<VolumeObject url='"tooth.obj"'/>)").find("a surface mesh has no voxels; the VolumeObject's voxelSize says"),
            std::string::npos);
  EXPECT_NE(errorIn(R"(<VolumeObject url='"tooth.obj"' voxelSize="0.0001 0.0001 0.0002" meshUnit="0.001"/>)")
                .find("a mesh is voxelised in cubic voxels"),
            std::string::npos);
  const std::string unknown =
      errorIn(R"(<VolumeObject url='"tooth.obj"' voxelSize="0.0001 0.0001 0.0001" meshUnit="0.001"><Tissue name="cementum"/></VolumeObject>)");
  EXPECT_NE(unknown.find("Tissue 'cementum' has neither densityRange nor label, and the mesh has no part of that name "
                         "(its parts: 'enamel', 'dentin', 'pulp')"),
            std::string::npos)
      << unknown;
  const std::string notMesh = errorIn(R"(<VolumeObject url='"phantom:tooth?size=32,32,22"'><Tissue name="enamel"/></VolumeObject>)");
  EXPECT_NE(notMesh.find(": error: Tissue 'enamel' has neither densityRange nor label, and the volume is not a mesh with parts to choose it by name"),
            std::string::npos)
      << notMesh;
}

}  // namespace
