// Micro-CT slice stacks (readSliceStack; issue 45, part 3): 16-bit TIFF slices
// in a folder, a printf pattern or one multi-page file, PNG and 8/24-bit BMP
// slices read voxel for voxel as the NRRD of the same data (TIFF in strips or tiles); the pixel size from the resolution tags or a
// SkyScan .log; slices sorted naturally; mismatched, truncated, colour and
// unsized stacks refused naming the file. The slices are written here with
// libtiff's writing API.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include <png.h>
#include <tiffio.h>

#include "TestFiles.h"
#include "millsim/core/NodeRegistry.h"
#include "millsim/volume/VolumeError.h"
#include "millsim/volume/VolumeIO.h"
#include "millsim/volume/VolumeObject.h"
#include "millsim/x3d/X3DLoader.h"

using namespace millsim;
using namespace millsim::test;
namespace fs = std::filesystem;

namespace {

constexpr int kW = 20, kH = 16, kSlices = 12;
constexpr float kAir = -1000.f;

// Slice z, pixel (x, y): distinct for every voxel, some of it air (0 is above kAir; 40000 past 32767).
std::uint16_t value(int x, int y, int z) { return std::uint16_t((x * 997 + y * 131 + z * 4099) % 40000); }

// One page (the current directory of `t`), 16-bit grey; `pixelMm` 0: no resolution tags.
void writePage(TIFF* t, int z, double pixelMm, int width = kW, int samples = 1) {
  TIFFSetField(t, TIFFTAG_IMAGEWIDTH, width);
  TIFFSetField(t, TIFFTAG_IMAGELENGTH, kH);
  TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, 16);
  TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, samples);
  TIFFSetField(t, TIFFTAG_PHOTOMETRIC, samples == 1 ? PHOTOMETRIC_MINISBLACK : PHOTOMETRIC_RGB);
  TIFFSetField(t, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
  TIFFSetField(t, TIFFTAG_ROWSPERSTRIP, 4);
  if (pixelMm > 0.0) {
    TIFFSetField(t, TIFFTAG_RESOLUTIONUNIT, RESUNIT_CENTIMETER);
    TIFFSetField(t, TIFFTAG_XRESOLUTION, float(10.0 / pixelMm));
    TIFFSetField(t, TIFFTAG_YRESOLUTION, float(10.0 / pixelMm));
  }
  std::vector<std::uint16_t> row(std::size_t(width * samples));
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < width * samples; ++x) row[std::size_t(x)] = value(x / samples, y, z);
    ASSERT_EQ(TIFFWriteScanline(t, row.data(), std::uint32_t(y), 0), 1);
  }
}

fs::path writeSlice(const fs::path& file, int z, double pixelMm, int width = kW, int samples = 1) {
  TIFF* t = TIFFOpen(file.c_str(), "w");
  EXPECT_NE(t, nullptr);
  writePage(t, z, pixelMm, width, samples);
  TIFFClose(t);
  return file;
}

// A 16-bit grey PNG slice (libpng's own writer: big-endian samples), with a
// pHYs chunk when pixelMm > 0; `colour` writes RGB instead (refused).
fs::path writePngSlice(const fs::path& file, int z, double pixelMm, bool colour = false) {
  std::FILE* f = std::fopen(file.c_str(), "wb");
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  png_init_io(png, f);
  png_set_IHDR(png, info, kW, kH, 16, colour ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (pixelMm > 0.0) {
    const png_uint_32 ppm = png_uint_32(std::lround(1000.0 / pixelMm));
    png_set_pHYs(png, info, ppm, ppm, PNG_RESOLUTION_METER);
  }
  png_write_info(png, info);
  std::vector<unsigned char> row(std::size_t(kW) * (colour ? 6 : 2));
  for (int y = 0; y < kH; ++y) {
    for (std::size_t i = 0; i < row.size() / 2; ++i) {
      const std::uint16_t v = value(int(colour ? i / 3 : i), y, z);
      row[2 * i] = static_cast<unsigned char>(v >> 8), row[2 * i + 1] = static_cast<unsigned char>(v & 0xff);
    }
    png_write_row(png, row.data());
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  std::fclose(f);
  return file;
}

// The same voxels as a NRRD, through the project's NRRD writer and reader.
VoxelVolume throughNrrd(const fs::path& dir) {
  std::vector<float> values;
  for (int z = 0; z < kSlices; ++z)
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) values.push_back(float(value(x, y, z)));
  const VoxelVolume v = VoxelVolume::fromDense(values.data(), {kW, kH, kSlices}, glm::dvec3(50e-6), kAir);
  writeNrrd(v, dir / "same.nrrd", false);
  return readNrrd(dir / "same.nrrd", kAir);
}

void expectSameVoxels(const VoxelVolume& a, const VoxelVolume& b) {
  ASSERT_EQ(a.dims(), b.dims());
  int differing = 0;
  for (int z = 0; z < kSlices; ++z)
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) differing += a.valueAt(x, y, z) != b.valueAt(x, y, z);
  EXPECT_EQ(differing, 0) << "voxels that differ from the NRRD of the same data";
}

std::string errorOf(const fs::path& source, glm::dvec3 voxelSize = glm::dvec3(0.0)) {
  try {
    readSliceStack(source, kAir, voxelSize);
  } catch (const VolumeError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SliceStack, AFolderOfSixteenBitSlicesIsTheNrrdOfTheSameData) {
  ScratchDir dir;
  fs::create_directories(dir.path() / "scan");
  // Named so that plain string order would be wrong: slice_2 after slice_10.
  for (int z = 0; z < kSlices; ++z) writeSlice(dir.path() / "scan" / ("slice_" + std::to_string(z) + ".tif"), z, 0.05);
  const VoxelVolume v = readSliceStack(dir.path() / "scan", kAir);
  EXPECT_NEAR(v.voxelSize().x, 50e-6, 1e-9) << "the pixel size from the resolution tags";
  EXPECT_NEAR(v.voxelSize().z, 50e-6, 1e-9);
  expectSameVoxels(v, throughNrrd(dir.path()));
}

// PNG slices (16-bit grey), by folder and by pattern: the same voxels, the pixel
// size from the pHYs chunk; a colour PNG, a folder of both kinds and a PNG cut
// short are clear errors.
TEST(SliceStack, SixteenBitPngSlicesAreTheNrrdOfTheSameData) {
  ScratchDir dir;
  fs::create_directories(dir.path() / "png");
  for (int z = 0; z < kSlices; ++z) writePngSlice(dir.path() / "png" / ("rec_" + std::to_string(z) + ".png"), z, 0.05);
  const VoxelVolume v = readSliceStack(dir.path() / "png", kAir);
  EXPECT_NEAR(v.voxelSize().x, 50e-6, 1e-9) << "the pixel size from the pHYs chunk";
  expectSameVoxels(v, throughNrrd(dir.path()));
  expectSameVoxels(readSliceStack(dir.path() / "png" / "rec_%d.png", kAir), v);

  fs::create_directories(dir.path() / "colour");
  writePngSlice(dir.path() / "colour" / "c_0.png", 0, 0.05, true);
  EXPECT_NE(errorOf(dir.path() / "colour").find("c_0.png is not one grey channel (PNG colour type 2)"), std::string::npos)
      << errorOf(dir.path() / "colour");
  writeSlice(dir.path() / "png" / "rec_99.tif", 0, 0.05);
  EXPECT_NE(errorOf(dir.path() / "png").find("holds both TIFF and PNG slices"), std::string::npos) << errorOf(dir.path() / "png");
  fs::remove(dir.path() / "png" / "rec_99.tif");
  fs::resize_file(dir.path() / "png" / "rec_5.png", fs::file_size(dir.path() / "png" / "rec_5.png") / 2);
  EXPECT_NE(errorOf(dir.path() / "png").find("rec_5.png: "), std::string::npos) << errorOf(dir.path() / "png");
  EXPECT_NE(errorOf(dir.path() / "png").find("is the file cut short?"), std::string::npos) << errorOf(dir.path() / "png");
}

TEST(SliceStack, APatternAndAMultiPageTiffReadTheSame) {
  ScratchDir dir;
  for (int z = 0; z < kSlices; ++z) {
    char name[32];
    std::snprintf(name, sizeof name, "img_%04d.tif", z + 1);
    writeSlice(dir.path() / name, z, 0.05);
  }
  const VoxelVolume nrrd = throughNrrd(dir.path());
  expectSameVoxels(readSliceStack(dir.path() / "img_%04d.tif", kAir), nrrd);

  TIFF* t = TIFFOpen((dir.path() / "stack.tif").c_str(), "w");
  ASSERT_NE(t, nullptr);
  for (int z = 0; z < kSlices; ++z) {
    writePage(t, z, 0.05);
    TIFFWriteDirectory(t);
  }
  TIFFClose(t);
  const LoadedVolume loaded = loadVolume((dir.path() / "stack.tif").string(), {}, kAir);
  EXPECT_EQ(loaded.format, "slices");
  expectSameVoxels(loaded.volume, nrrd);
}

// One tiled 16-bit page: 16 × 16 tiles, so a 20-pixel row spans two tiles and
// the second overhangs the page (libtiff pads it; the reader must not keep the padding).
fs::path writeTiledSlice(const fs::path& file, int z, double pixelMm) {
  TIFF* t = TIFFOpen(file.c_str(), "w");
  EXPECT_NE(t, nullptr);
  TIFFSetField(t, TIFFTAG_IMAGEWIDTH, kW);
  TIFFSetField(t, TIFFTAG_IMAGELENGTH, kH);
  TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, 16);
  TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, 1);
  TIFFSetField(t, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_MINISBLACK);
  TIFFSetField(t, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
  TIFFSetField(t, TIFFTAG_TILEWIDTH, 16);
  TIFFSetField(t, TIFFTAG_TILELENGTH, 16);
  TIFFSetField(t, TIFFTAG_RESOLUTIONUNIT, RESUNIT_CENTIMETER);
  TIFFSetField(t, TIFFTAG_XRESOLUTION, float(10.0 / pixelMm));
  TIFFSetField(t, TIFFTAG_YRESOLUTION, float(10.0 / pixelMm));
  std::vector<std::uint16_t> tile(16 * 16);
  for (int x0 = 0; x0 < kW; x0 += 16) {
    for (int r = 0; r < 16; ++r)
      for (int c = 0; c < 16; ++c)
        tile[std::size_t(r * 16 + c)] = x0 + c < kW && r < kH ? value(x0 + c, r, z) : std::uint16_t(12345);
    EXPECT_GT(TIFFWriteTile(t, tile.data(), std::uint32_t(x0), 0, 0, 0), 0);
  }
  TIFFClose(t);
  return file;
}

TEST(SliceStack, TiledTiffSlicesReadAsTheNrrdOfTheSameData) {
  ScratchDir dir;
  fs::create_directories(dir.path() / "tiles");
  for (int z = 0; z < kSlices; ++z) writeTiledSlice(dir.path() / "tiles" / ("t" + std::to_string(z) + ".tif"), z, 0.05);
  const VoxelVolume v = readSliceStack(dir.path() / "tiles", kAir);
  EXPECT_NEAR(v.voxelSize().x, 50e-6, 1e-12);
  expectSameVoxels(v, throughNrrd(dir.path()));

  fs::resize_file(dir.path() / "tiles" / "t3.tif", fs::file_size(dir.path() / "tiles" / "t3.tif") / 2);
  const std::string cut = errorOf(dir.path() / "tiles");
  EXPECT_NE(cut.find("t3.tif"), std::string::npos) << cut;
  EXPECT_EQ(cut.find("(no error)"), std::string::npos);
}

// An 8-bit grey value for slice z, pixel (x, y): BMP slices are 8-bit.
std::uint8_t grey(int x, int y, int z) { return std::uint8_t((x * 37 + y * 11 + z * 101) % 256); }

// A BMP slice written byte by byte (the format's own layout, not a library's
// writer): 8-bit with a grey palette, bottom-up as most tools write it, or
// 24-bit top-down (negative height); `colourAt` makes one pixel not grey.
fs::path writeBmpSlice(const fs::path& file, int z, int bits, bool topDown, bool colourAt = false) {
  const int bytes = bits / 8, stride = (kW * bytes + 3) / 4 * 4, paletteBytes = bits == 8 ? 256 * 4 : 0;
  const std::uint32_t offset = 14 + 40 + std::uint32_t(paletteBytes), size = offset + std::uint32_t(stride * kH);
  std::vector<unsigned char> b;
  auto put = [&](std::uint32_t v, int n) {
    for (int i = 0; i < n; ++i) b.push_back(static_cast<unsigned char>(v >> (8 * i)));
  };
  b.push_back('B'), b.push_back('M');
  put(size, 4), put(0, 4), put(offset, 4);
  put(40, 4), put(kW, 4), put(std::uint32_t(topDown ? -kH : kH), 4), put(1, 2), put(std::uint32_t(bits), 2);
  put(0, 4), put(std::uint32_t(stride * kH), 4), put(2835, 4), put(2835, 4), put(bits == 8 ? 256 : 0, 4), put(0, 4);
  for (int i = 0; i < paletteBytes / 4; ++i) put(std::uint32_t(i) * 0x010101u, 4);
  for (int r = 0; r < kH; ++r) {
    const int y = topDown ? r : kH - 1 - r;
    for (int x = 0; x < kW; ++x) {
      const std::uint8_t g = grey(x, y, z);
      if (bits == 8) b.push_back(g);
      else b.push_back(g), b.push_back(colourAt && x == 3 && y == 5 ? std::uint8_t(g ^ 1) : g), b.push_back(g);
    }
    for (int pad = kW * bytes; pad < stride; ++pad) b.push_back(0);
  }
  std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
  return file;
}

TEST(SliceStack, EightAndTwentyFourBitBmpSlicesAreTheNrrdOfTheSameData) {
  ScratchDir dir;
  std::vector<float> values;
  for (int z = 0; z < kSlices; ++z)
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) values.push_back(float(grey(x, y, z)));
  writeNrrd(VoxelVolume::fromDense(values.data(), {kW, kH, kSlices}, glm::dvec3(20e-6), kAir), dir.path() / "grey.nrrd", false);
  const VoxelVolume nrrd = readNrrd(dir.path() / "grey.nrrd", kAir);

  fs::create_directories(dir.path() / "bmp8");
  fs::create_directories(dir.path() / "bmp24");
  for (int z = 0; z < kSlices; ++z) {
    writeBmpSlice(dir.path() / "bmp8" / ("rec" + std::to_string(z) + ".bmp"), z, 8, false);
    writeBmpSlice(dir.path() / "bmp24" / ("rec" + std::to_string(z) + ".bmp"), z, 24, true);
  }
  // A BMP's pixels per metre (72 dpi here, as tools write whatever the scan) is not a pixel size.
  EXPECT_NE(errorOf(dir.path() / "bmp8").find("no pixel size in a SkyScan .log beside the slices"), std::string::npos)
      << errorOf(dir.path() / "bmp8");
  dir.write("bmp8/rec.log", "[Reconstruction]\nImage Pixel Size (um)=20.0\n");
  const VoxelVolume v = readSliceStack(dir.path() / "bmp8", kAir);
  EXPECT_NEAR(v.voxelSize().x, 20e-6, 1e-12);
  expectSameVoxels(v, nrrd);
  expectSameVoxels(readSliceStack(dir.path() / "bmp24" / "rec%d.bmp", kAir, glm::dvec3(20e-6)), nrrd);
  const LoadedVolume loaded = loadVolume((dir.path() / "bmp8").string(), {}, kAir);
  EXPECT_EQ(loaded.format, "slices");
}

TEST(SliceStack, BadBmpSlicesAreRefusedNamingTheFile) {
  ScratchDir dir;
  const glm::dvec3 h(20e-6);
  fs::create_directories(dir.path() / "colour");
  writeBmpSlice(dir.path() / "colour" / "c0.bmp", 0, 24, false, true);
  EXPECT_NE(errorOf(dir.path() / "colour", h).find("c0.bmp is not greyscale: pixel (3, 5) is ("), std::string::npos)
      << errorOf(dir.path() / "colour", h);

  fs::create_directories(dir.path() / "cut");
  const fs::path cut = writeBmpSlice(dir.path() / "cut" / "c0.bmp", 0, 8, false);
  fs::resize_file(cut, fs::file_size(cut) - 100);
  EXPECT_NE(errorOf(dir.path() / "cut", h).find("c0.bmp: not a BMP SDL2 can read"), std::string::npos)
      << errorOf(dir.path() / "cut", h);

  // A header of 60000 × 60000 pixels is refused before anything is allocated for it.
  fs::create_directories(dir.path() / "huge");
  std::string huge(54, '\0');
  huge[0] = 'B', huge[1] = 'M', huge[14] = 40, huge[18] = char(0x60), huge[19] = char(0xea), huge[22] = char(0x60),
  huge[23] = char(0xea), huge[26] = 1, huge[28] = 8;
  dir.write("huge/h0.bmp", huge);
  EXPECT_NE(errorOf(dir.path() / "huge", h).find("h0.bmp is 60000 × 60000 pixels; a BMP slice is read whole"),
            std::string::npos)
      << errorOf(dir.path() / "huge", h);
  dir.write("huge/h0.bmp", "BM");
  EXPECT_NE(errorOf(dir.path() / "huge", h).find("h0.bmp: its BMP header is cut short (2 bytes)"), std::string::npos)
      << errorOf(dir.path() / "huge", h);
  dir.write("huge/h0.bmp", "not a bitmap at all");
  EXPECT_NE(errorOf(dir.path() / "huge", h).find("h0.bmp: not a BMP file"), std::string::npos) << errorOf(dir.path() / "huge", h);

  fs::create_directories(dir.path() / "mixed");
  writeBmpSlice(dir.path() / "mixed" / "m0.bmp", 0, 8, false);
  writeSlice(dir.path() / "mixed" / "m1.tif", 1, 0.05);
  EXPECT_NE(errorOf(dir.path() / "mixed", h).find("holds both TIFF and BMP slices"), std::string::npos)
      << errorOf(dir.path() / "mixed", h);
}

TEST(SliceStack, ASkyScanLogGivesThePixelSize) {
  ScratchDir dir;
  for (int z = 0; z < 3; ++z) writeSlice(dir.path() / ("rec" + std::to_string(z) + ".tif"), z, 0.0);
  EXPECT_NE(errorOf(dir.path()).find("no pixel size in the TIFF resolution tags or in a SkyScan .log"), std::string::npos)
      << errorOf(dir.path());
  EXPECT_NEAR(readSliceStack(dir.path(), kAir, glm::dvec3(20e-6)).voxelSize().x, 20e-6, 1e-12) << "the VolumeObject's";
  dir.write("rec.log", "[Reconstruction]\nImage Pixel Size (um)=12.500\n");
  EXPECT_NEAR(readSliceStack(dir.path(), kAir).voxelSize().y, 12.5e-6, 1e-12);
}

TEST(SliceStack, BadStacksAreRefusedNamingTheFile) {
  ScratchDir dir;
  fs::create_directories(dir.path() / "sizes");
  writeSlice(dir.path() / "sizes" / "a1.tif", 0, 0.05);
  writeSlice(dir.path() / "sizes" / "a2.tif", 1, 0.05, kW + 3);
  EXPECT_NE(errorOf(dir.path() / "sizes").find("a2.tif is 23 × 16 pixels of 16-bit integers; the first slice, a1.tif, is 20 × 16 pixels of 16-bit integers"),
            std::string::npos)
      << errorOf(dir.path() / "sizes");

  fs::create_directories(dir.path() / "colour");
  writeSlice(dir.path() / "colour" / "c.tif", 0, 0.05, kW, 3);
  EXPECT_NE(errorOf(dir.path() / "colour").find("c.tif has 3 samples a pixel; a slice is one grey channel"), std::string::npos)
      << errorOf(dir.path() / "colour");

  fs::create_directories(dir.path() / "cut");
  const fs::path whole = writeSlice(dir.path() / "cut" / "b.tif", 0, 0.05);
  const auto bytes = fs::file_size(whole);
  fs::resize_file(whole, bytes / 2);
  const std::string cut = errorOf(dir.path() / "cut");
  EXPECT_EQ(cut.rfind((dir.path() / "cut").string(), 0), 0u) << "a truncated slice is an error naming it: " << cut;
  EXPECT_EQ(cut.find("(no error)"), std::string::npos);

  EXPECT_NE(errorOf(dir.path() / "none_%03d.tif").find("no slice file matches the pattern"), std::string::npos);
}

TEST(SliceStack, AVolumeObjectLoadsAFolderOfSlices) {
  ScratchDir dir;
  fs::create_directories(dir.path() / "scan");
  for (int z = 0; z < kSlices; ++z) writeSlice(dir.path() / "scan" / ("s" + std::to_string(z) + ".tif"), z, 0.05);
  // Unsized slices take the VolumeObject's voxelSize.
  fs::create_directories(dir.path() / "unsized");
  for (int z = 0; z < 3; ++z) writeSlice(dir.path() / "unsized" / ("u" + std::to_string(z) + ".tif"), z, 0.0);
  LoadResult u = loadSceneFile(
      dir.write("u.x3d", x3d(R"(<VolumeObject DEF="U" url='"unsized"' voxelSize="0.00002 0.00002 0.00002" isoValue="20000"/>)")),
      builtinRegistry());
  ASSERT_TRUE(u.ok()) << u.report();
  EXPECT_NEAR(dynamic_cast<const VolumeObject*>(u.scene->def("U").get())->voxelEdge(), 20e-6, 1e-12);
  LoadResult r = loadSceneFile(
      dir.write("s.x3d", x3d(R"(<VolumeObject DEF="V" url='"scan"' isoValue="20000" airValue="-1000"/>)")), builtinRegistry());
  ASSERT_TRUE(r.ok()) << r.report();
  const auto* v = dynamic_cast<const VolumeObject*>(r.scene->def("V").get());
  ASSERT_NE(v, nullptr);
  EXPECT_EQ(v->format(), "slices");
  EXPECT_EQ(v->volume()->dims(), glm::ivec3(kW, kH, kSlices));
}

}  // namespace
