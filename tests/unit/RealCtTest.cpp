// The readers on a real CT (x3d/data/ct: VTK's quarter-resolution head scan,
// Kitware's BSD-3 data, the same voxels in three formats): the NRRD against
// an independent decode of its gzip payload, voxel for voxel, and the
// MetaImage (zlib, read by VTK) and the VTI (appended raw) against the NRRD.
// Hand-written test files check each encoding; this checks that a scanner's
// file, with its noise, its spacing and its int16 CT numbers, reads as it is.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <zlib.h>

#include "millsim/volume/VolumeIO.h"
#include "millsim/volume/VoxelVolume.h"

using namespace millsim;
namespace fs = std::filesystem;

namespace {

const fs::path kCt = fs::path(MILLSIM_SOURCE_DIR) / "x3d/data/ct";
constexpr float kAir = 400.f;  // CT numbers of this scan: air about 0, soft tissue 1000-1200, bone above 1500
const glm::ivec3 kDims(64, 64, 93);

// The NRRD's int16 voxels, decoded here with zlib alone (the header ends at
// the first blank line; "encoding: gzip", little-endian "short").
std::vector<std::int16_t> decodeNrrdByHand(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t start = bytes.find("\n\n");
  EXPECT_NE(start, std::string::npos) << "no blank line after the NRRD header";
  z_stream zs{};
  EXPECT_EQ(inflateInit2(&zs, 15 + 16), Z_OK);
  std::vector<std::int16_t> voxels(std::size_t(kDims.x) * kDims.y * kDims.z);
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data() + start + 2));
  zs.avail_in = uInt(bytes.size() - start - 2);
  zs.next_out = reinterpret_cast<Bytef*>(voxels.data());
  zs.avail_out = uInt(voxels.size() * sizeof(std::int16_t));
  EXPECT_EQ(inflate(&zs, Z_FINISH), Z_STREAM_END) << "the gzip payload should hold exactly 64 x 64 x 93 shorts";
  EXPECT_EQ(zs.avail_out, 0u);
  inflateEnd(&zs);
  return voxels;
}

}  // namespace

TEST(RealCt, TheHeadScanReadsAsItsOwnBytesSay) {
  const VoxelVolume v = readNrrd(kCt / "headsq_gzip.nrrd", kAir);
  ASSERT_EQ(v.dims(), kDims);
  EXPECT_DOUBLE_EQ(v.voxelSize().x, 3.2e-3);
  EXPECT_DOUBLE_EQ(v.voxelSize().y, 3.2e-3);
  EXPECT_DOUBLE_EQ(v.voxelSize().z, 1.5e-3);
  const std::vector<std::int16_t> raw = decodeNrrdByHand(kCt / "headsq_gzip.nrrd");
  std::uint64_t material = 0, teeth = 0, wrong = 0;
  for (int k = 0; k < kDims.z; ++k)
    for (int j = 0; j < kDims.y; ++j)
      for (int i = 0; i < kDims.x; ++i) {
        const float want = raw[(std::size_t(k) * kDims.y + j) * kDims.x + i];
        // At or below air the reader keeps no value: the voxel reads as air.
        const float expected = want > kAir ? want : kAir;
        if (v.valueAt(i, j, k) != expected && ++wrong <= 5)
          ADD_FAILURE() << "voxel (" << i << ", " << j << ", " << k << ") reads " << v.valueAt(i, j, k)
                        << ", the file holds " << want;
        material += want > kAir, teeth += want > 2600;
      }
  EXPECT_EQ(wrong, 0u);
  EXPECT_EQ(v.activeVoxels(), material);
  // The densest voxels (above 2600, mostly the teeth: the lesson's "teeth" tissue), counted by an
  // independent histogram (numpy) when the lesson was written.
  EXPECT_EQ(teeth, 503u);
}

TEST(RealCt, TheSameScanReadsTheSameInEveryFormat) {
  const VoxelVolume nrrd = readNrrd(kCt / "headsq_gzip.nrrd", kAir);
  const VoxelVolume mha = readMetaImage(kCt / "headsq_zlib.mha", kAir);
  const VoxelVolume vti = readVti(kCt / "headsq_appended_raw.vti", kAir);
  for (const VoxelVolume* other : {&mha, &vti}) {
    EXPECT_EQ(other->dims(), nrrd.dims());
    EXPECT_EQ(other->voxelSize(), nrrd.voxelSize());
    EXPECT_EQ(other->activeVoxels(), nrrd.activeVoxels());
    EXPECT_EQ(other->contentHash(), nrrd.contentHash());
  }
  // loadVolume finds each by its extension, relative to the folder it is given.
  EXPECT_EQ(loadVolume("headsq_zlib.mha", kCt, kAir).format, "metaimage");
  EXPECT_EQ(loadVolume("headsq_appended_raw.vti", kCt, kAir).volume.contentHash(), nrrd.contentHash());
}
