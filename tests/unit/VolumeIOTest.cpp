// Volume readers and writers: NRRD, MetaImage, VTI, OpenVDB, DICOM (GDCM) and loadVolume.
//
// Test files are written at test time into scratch folders: by hand (text
// headers + bytes, zlib for compressed data) so that each reader is checked
// against an independent writer, and DICOM with pydicom (/usr/bin/python3;
// Debian's python3-pydicom), which also computes the expected Hounsfield values.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <openvdb/io/File.h>
#include <openvdb/tools/Prune.h>
#include <zlib.h>

#include "TestFiles.h"
#include "ZlibCompress.h"
#include "millsim/volume/VolumeIO.h"
#include "millsim/volume/VoxelVolume.h"

using namespace millsim;
using millsim::test::ScratchDir;
namespace fs = std::filesystem;

namespace {

const fs::path kPydicomFiles = "/usr/lib/python3/dist-packages/pydicom/data/test_files";
const char* const kPython = "/usr/bin/python3";

// ---- helpers ---------------------------------------------------------------

fs::path writeBytes(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  return p;
}

std::string readBytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

template <typename T>
std::string le(const std::vector<T>& v) {  // little-endian bytes
  std::string s(v.size() * sizeof(T), '\0');
  std::memcpy(s.data(), v.data(), s.size());
  return s;
}

template <typename T>
std::string be(const std::vector<T>& v) {  // big-endian bytes
  std::string s = le(v);
  for (std::size_t i = 0; i < s.size(); i += sizeof(T)) std::reverse(s.begin() + long(i), s.begin() + long(i + sizeof(T)));
  return s;
}

using millsim::test::compress;

// Runs a python script with Debian's python3 (which has pydicom); returns stdout, fails the test on error.
std::string runPython(const fs::path& script, const std::string& args) {
  const std::string cmd = std::string(kPython) + " '" + script.string() + "' " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) {
    ADD_FAILURE() << "cannot run " << cmd;
    return {};
  }
  std::string out;
  char buf[4096];
  for (std::size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
  const int rc = pclose(p);
  EXPECT_EQ(rc, 0) << cmd << "\n" << out;
  return out;
}

// The VolumeError message of f(), or "" (and a test failure) when f does not throw one.
// MILLSIM_SHOW_ERRORS=1 prints every message, to review their wording.
std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const VolumeError& e) {
    if (std::getenv("MILLSIM_SHOW_ERRORS")) std::printf("ERRMSG %s\n", e.what());
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected VolumeError, got another exception: " << e.what();
    return {};
  }
  ADD_FAILURE() << "expected VolumeError, nothing was thrown";
  return {};
}

// Checks that f() throws a VolumeError whose message starts with the file's path and contains phrase.
#define EXPECT_VOLUME_ERROR(call, file, phrase)                                                     \
  do {                                                                                              \
    const std::string msg_ = errorOf([&] { (void)(call); });                                        \
    EXPECT_EQ(msg_.rfind(fs::path(file).string(), 0), 0u) << "message should start with the path: " << msg_; \
    EXPECT_NE(msg_.find(phrase), std::string::npos) << "message should contain '" << (phrase) << "': " << msg_; \
  } while (0)

// Expected value of the synthetic test volumes.
float pattern(int i, int j, int k) { return float(i + 20 * j + 200 * k - 500); }

std::vector<float> patternValues(glm::ivec3 d) {
  std::vector<float> v;
  for (int k = 0; k < d.z; ++k)
    for (int j = 0; j < d.y; ++j)
      for (int i = 0; i < d.x; ++i) v.push_back(pattern(i, j, k));
  return v;
}

template <typename T>
std::vector<T> cast(const std::vector<float>& v) {
  return std::vector<T>(v.begin(), v.end());
}

void expectPattern(const VoxelVolume& vol, glm::ivec3 d, glm::dvec3 spacingMm) {
  ASSERT_EQ(vol.dims(), d);
  for (int a = 0; a < 3; ++a) EXPECT_DOUBLE_EQ(vol.voxelSize()[a], spacingMm[a] / 1000.0) << "axis " << a;
  int wrong = 0;
  for (int k = 0; k < d.z; ++k)
    for (int j = 0; j < d.y; ++j)
      for (int i = 0; i < d.x; ++i)
        if (vol.valueAt(i, j, k) != pattern(i, j, k) && ++wrong < 5)
          ADD_FAILURE() << "voxel (" << i << "," << j << "," << k << ") is " << vol.valueAt(i, j, k) << ", expected "
                        << pattern(i, j, k);
  EXPECT_EQ(wrong, 0);
}

const float kAir = -2000.f;  // below every test value, so nothing is clamped to air

std::string nrrdHeader(const std::string& type, glm::ivec3 d, const std::string& spacingLine, const std::string& encoding,
                       const std::string& endian = "little") {
  std::ostringstream h;
  h << "NRRD0004\n# written by hand in VolumeIOTest\ntype: " << type << "\ndimension: 3\nsizes: " << d.x << " " << d.y
    << " " << d.z << "\n"
    << spacingLine << "\nencoding: " << encoding << "\n";
  if (!endian.empty()) h << "endian: " << endian << "\n";
  h << "\n";
  return h.str();
}

std::string mhaHeader(const std::string& type, glm::ivec3 d, const std::string& spacing, const std::string& extra,
                      const std::string& dataFile = "LOCAL", bool bigEndian = false) {
  std::ostringstream h;
  h << "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = " << (bigEndian ? "True" : "False")
    << "\n" << extra
    << "ElementSpacing = " << spacing << "\nDimSize = " << d.x << " " << d.y << " " << d.z << "\nElementType = " << type
    << "\nElementDataFile = " << dataFile << "\n";
  return h.str();
}

std::string vtiFile(glm::ivec3 d, const std::string& spacing, const std::string& values, const std::string& type = "Int16",
                    int components = 1) {
  std::ostringstream x;
  x << "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
    << "<ImageData WholeExtent=\"0 " << d.x - 1 << " 0 " << d.y - 1 << " 0 " << d.z - 1 << "\" Origin=\"0 0 0\" Spacing=\""
    << spacing << "\">\n<Piece Extent=\"0 " << d.x - 1 << " 0 " << d.y - 1 << " 0 " << d.z - 1
    << "\">\n<PointData Scalars=\"density\">\n<DataArray type=\"" << type << "\" Name=\"density\" NumberOfComponents=\""
    << components << "\" format=\"ascii\">\n"
    << values << "\n</DataArray>\n</PointData>\n<CellData/>\n</Piece>\n</ImageData>\n</VTKFile>\n";
  return x.str();
}

std::string asciiValues(const std::vector<float>& v) {
  std::ostringstream s;
  for (std::size_t i = 0; i < v.size(); ++i) s << v[i] << ((i % 16 == 15) ? "\n" : " ");
  return s.str();
}

// ---- DICOM: the pydicom script ----------------------------------------------

// Modes: "dump FILE" prints Rows Columns PixelSpacing[0] PixelSpacing[1] SliceThickness, then every
// pixel's HU (stored value x RescaleSlope + RescaleIntercept) row by row;
// "series DIR" writes 5 CT slices (see DicomSeries test); "mr DIR" writes one MR slice.
const char* const kDicomScript = R"PY(#!/usr/bin/python3
import sys
import numpy as np
import pydicom
from pydicom.dataset import FileDataset, FileMetaDataset
from pydicom.uid import ExplicitVRLittleEndian, generate_uid

mode, target = sys.argv[1], sys.argv[2]
if mode == "dump":
    ds = pydicom.dcmread(target)
    hu = ds.pixel_array.astype(np.float64) * float(ds.get("RescaleSlope", 1)) + float(ds.get("RescaleIntercept", 0))
    print(ds.Rows, ds.Columns, float(ds.PixelSpacing[0]), float(ds.PixelSpacing[1]), float(ds.SliceThickness))
    for row in hu:
        print(" ".join(repr(float(v)) for v in row))
    sys.exit(0)

def slice_file(path, modality, series, k, position, orientation):
    meta = FileMetaDataset()
    meta.MediaStorageSOPClassUID = "1.2.840.10008.5.1.4.1.1.2" if modality == "CT" else "1.2.840.10008.5.1.4.1.1.4"
    meta.MediaStorageSOPInstanceUID = generate_uid()
    meta.TransferSyntaxUID = ExplicitVRLittleEndian
    ds = FileDataset(path, {}, file_meta=meta, preamble=b"\0" * 128)
    ds.is_little_endian = True
    ds.is_implicit_VR = False
    ds.SOPClassUID = meta.MediaStorageSOPClassUID
    ds.SOPInstanceUID = meta.MediaStorageSOPInstanceUID
    ds.Modality = modality
    ds.SeriesInstanceUID = series
    ds.InstanceNumber = k + 1
    ds.Rows, ds.Columns = 12, 16
    ds.SamplesPerPixel = 1
    ds.PhotometricInterpretation = "MONOCHROME2"
    ds.BitsAllocated, ds.BitsStored, ds.HighBit, ds.PixelRepresentation = 16, 16, 15, 1
    ds.PixelSpacing = [0.7, 0.4]          # between rows, between columns (mm)
    ds.SliceThickness = 3.0               # deliberately not the slice spacing (2.5)
    ds.ImageOrientationPatient = orientation
    ds.ImagePositionPatient = position
    ds.RescaleSlope = 2
    ds.RescaleIntercept = -1000
    rows, cols = np.mgrid[0:12, 0:16]
    stored = (k * 1000 + rows * 16 + cols).astype("<i2")   # HU = 2 * stored - 1000
    ds.PixelData = stored.tobytes()
    ds.save_as(path, write_like_original=False)

series = generate_uid()
if mode == "series":
    # Coronal slices: rows along +x, columns along -z, so the normal is +y. Slice k sits at
    # y = 5 + 2.5 k; files are named so that their name order is not the slice order.
    names = ["c.dcm", "a.dcm", "e.dcm", "b.dcm", "d.dcm"]   # slice k is in names[k]
    for k, name in enumerate(names):
        slice_file(target + "/" + name, "CT", series, k, [-20.0 + 0.3 * k, 5.0 + 2.5 * k, 40.0], [1, 0, 0, 0, 0, -1])
elif mode == "mr":
    slice_file(target + "/mr.dcm", "MR", series, 0, [0.0, 0.0, 0.0], [1, 0, 0, 0, 1, 0])
)PY";

fs::path dicomScript(const ScratchDir& dir) { return dir.write("dicom.py", kDicomScript); }

}  // namespace

// ---- DICOM --------------------------------------------------------------------

TEST(VolumeIODicom, CtSmallMatchesPydicom) {
  const fs::path file = kPydicomFiles / "CT_small.dcm";
  ASSERT_TRUE(fs::exists(file)) << "python3-pydicom is not installed (scripts/setup)";
  ScratchDir dir;
  std::istringstream dump(runPython(dicomScript(dir), "dump '" + file.string() + "'"));
  int rows = 0, cols = 0;
  double rowSpacing = 0, colSpacing = 0, thickness = 0;
  dump >> rows >> cols >> rowSpacing >> colSpacing >> thickness;
  ASSERT_EQ(rows, 128);
  ASSERT_EQ(cols, 128);
  std::vector<double> hu(std::size_t(rows) * std::size_t(cols));
  for (double& v : hu) dump >> v;
  ASSERT_TRUE(dump) << "pydicom output ended early";
  auto at = [&](int r, int c) { return hu[std::size_t(r) * std::size_t(cols) + std::size_t(c)]; };
  // The image is not symmetric, so a row/column mix-up cannot pass unnoticed.
  int asymmetric = 0;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < r; ++c) asymmetric += at(r, c) != at(c, r);
  ASSERT_GT(asymmetric, 1000);

  const VoxelVolume vol = readDicom(file, kAir);
  ASSERT_EQ(vol.dims(), glm::ivec3(cols, rows, 1));
  EXPECT_DOUBLE_EQ(vol.voxelSize().x, colSpacing / 1000.0);
  EXPECT_DOUBLE_EQ(vol.voxelSize().y, rowSpacing / 1000.0);
  EXPECT_DOUBLE_EQ(vol.voxelSize().z, thickness / 1000.0);  // one slice: SliceThickness
  // i = DICOM column, j = DICOM row (j = 0 is the top row, j grows downwards).
  int wrong = 0;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      if (double(vol.valueAt(c, r, 0)) != at(r, c) && ++wrong < 5)
        ADD_FAILURE() << "row " << r << " column " << c << ": " << vol.valueAt(c, r, 0) << " HU, pydicom says " << at(r, c);
  EXPECT_EQ(wrong, 0);
  EXPECT_LT(*std::min_element(hu.begin(), hu.end()), -500.0);  // the intercept (-1024) was applied

  const LoadedVolume loaded = loadVolume(file.string(), "", kAir);
  EXPECT_EQ(loaded.format, "dicom");
  EXPECT_EQ(loaded.volume.contentHash(), vol.contentHash());
}

TEST(VolumeIODicom, SeriesIsOrderedByPositionWithSpacingAndHU) {
  ScratchDir dir;
  const fs::path series = dir.path() / "series";
  fs::create_directories(series);
  runPython(dicomScript(dir), "series '" + series.string() + "'");
  dir.write("series/notes.txt", "not a DICOM file: skipped\n");

  for (const fs::path& source : {series, series / "."}) {
    const VoxelVolume vol = readDicom(source, kAir);
    ASSERT_EQ(vol.dims(), glm::ivec3(16, 12, 5));
    EXPECT_NEAR(vol.voxelSize().x, 0.4e-3, 1e-12);  // between columns
    EXPECT_NEAR(vol.voxelSize().y, 0.7e-3, 1e-12);  // between rows
    EXPECT_NEAR(vol.voxelSize().z, 2.5e-3, 1e-9);   // from the positions, not SliceThickness (3.0)
    int wrong = 0;
    for (int k = 0; k < 5; ++k)
      for (int j = 0; j < 12; ++j)
        for (int i = 0; i < 16; ++i) {
          const float expected = 2.f * float(k * 1000 + j * 16 + i) - 1000.f;
          if (vol.valueAt(i, j, k) != expected && ++wrong < 5)
            ADD_FAILURE() << "(" << i << "," << j << "," << k << ") = " << vol.valueAt(i, j, k) << ", expected " << expected;
        }
    EXPECT_EQ(wrong, 0);
  }
  const LoadedVolume loaded = loadVolume("series", dir.path(), kAir);  // relative to baseDir
  EXPECT_EQ(loaded.format, "dicom");
  EXPECT_EQ(loaded.volume.dims(), glm::ivec3(16, 12, 5));

  // A missing slice makes the spacing uneven: refused, not stretched.
  fs::remove(series / "e.dcm");  // slice 2
  EXPECT_VOLUME_ERROR(readDicom(series, kAir), series, "not uniform");
}

TEST(VolumeIODicom, RefusesOtherModalities) {
  EXPECT_VOLUME_ERROR(readDicom(kPydicomFiles / "MR_small.dcm", kAir), kPydicomFiles / "MR_small.dcm", "modality is MR");
  ScratchDir dir;
  runPython(dicomScript(dir), "mr '" + dir.path().string() + "'");
  EXPECT_VOLUME_ERROR(readDicom(dir.path(), kAir), dir.path() / "mr.dcm", "modality is MR, not CT");
}

TEST(VolumeIODicom, TruncatedFilesAreErrors) {
  EXPECT_VOLUME_ERROR(readDicom(kPydicomFiles / "MR_truncated.dcm", kAir), kPydicomFiles / "MR_truncated.dcm", "truncated");
  ScratchDir dir;
  const std::string ct = readBytes(kPydicomFiles / "CT_small.dcm");
  ASSERT_GT(ct.size(), 30000u);
  // Cut inside the pixel data, inside the header, and inside a sequence item (which makes
  // Debian's GDCM abort on an assertion unless the file is checked first).
  for (std::size_t cut : {std::size_t(20000), std::size_t(1000), std::size_t(700), std::size_t(300)}) {
    const fs::path f = writeBytes(dir.path() / ("ct_cut_" + std::to_string(cut) + ".dcm"), ct.substr(0, cut));
    EXPECT_VOLUME_ERROR(readDicom(f, kAir), f, "truncated");
  }
}

TEST(VolumeIODicom, EmptyFolderAndNonDicomFile) {
  ScratchDir dir;
  EXPECT_VOLUME_ERROR(readDicom(dir.path(), kAir), dir.path(), "no DICOM files in " + dir.path().string());
  EXPECT_VOLUME_ERROR(loadVolume(dir.path().string(), "", kAir), dir.path(), "no DICOM files in");
  const fs::path txt = dir.write("slice.dcm", "hello\n");
  EXPECT_VOLUME_ERROR(readDicom(txt, kAir), txt, "not a DICOM file");
}

// ---- NRRD ---------------------------------------------------------------------

TEST(VolumeIONrrd, HandWrittenEncodingsTypesAndLayouts) {
  ScratchDir dir;
  const glm::ivec3 d(11, 7, 5);
  const glm::dvec3 mm(0.5, 0.25, 2.0);
  const auto v = patternValues(d);
  const std::string spacings = "spacings: 0.5 0.25 2";
  const std::string directions = "space: left-posterior-superior\nspace directions: (0.5,0,0) (0,-0.25,0) (0,0,2)";

  const auto raw16 = writeBytes(dir.path() / "raw16.nrrd", nrrdHeader("short", d, spacings, "raw") + le(cast<std::int16_t>(v)));
  expectPattern(readNrrd(raw16, kAir), d, mm);
  const auto gzBig = writeBytes(dir.path() / "gz_big.nrrd",
                                nrrdHeader("int32", d, directions, "gzip", "big") + compress(be(cast<std::int32_t>(v)), 31));
  expectPattern(readNrrd(gzBig, kAir), d, mm);
  const auto gzDouble = writeBytes(dir.path() / "gz_double.nrrd",
                                   nrrdHeader("double", d, spacings, "gz") + compress(le(cast<double>(v)), 31));
  expectPattern(readNrrd(gzDouble, kAir), d, mm);
  const auto ascii = dir.write("ascii.nrrd", nrrdHeader("float", d, spacings, "ascii", "") + asciiValues(v));
  expectPattern(readNrrd(ascii, kAir), d, mm);
  // "space: left-anterior-superior" must not flip rows (VTK 9.1's reader does).
  const std::string las = "space: left-anterior-superior\nspace directions: (-0.5,0,0) (0,-0.25,0) (0,0,2)";
  const auto lasFile = writeBytes(dir.path() / "las.nrrd", nrrdHeader("short", d, las, "raw", "big") + be(cast<std::int16_t>(v)));
  expectPattern(readNrrd(lasFile, kAir), d, mm);

  // A first size of 9 or less is still one component per voxel (VTK 9.1 guesses components).
  const glm::ivec3 narrow(4, 6, 3);
  const auto nv = patternValues(narrow);
  {
    // uint16 cannot hold the negative pattern: write pattern + 1000.
    std::vector<std::uint16_t> u;
    for (float x : nv) u.push_back(std::uint16_t(x + 1000.f));
    const auto narrowFile = writeBytes(dir.path() / "narrow.nrrd", nrrdHeader("uint16", narrow, spacings, "raw") + le(u));
    const VoxelVolume vol = readNrrd(narrowFile, kAir);
    ASSERT_EQ(vol.dims(), narrow);
    EXPECT_EQ(vol.valueAt(3, 5, 2), pattern(3, 5, 2) + 1000.f);
    EXPECT_EQ(vol.valueAt(1, 0, 1), pattern(1, 0, 1) + 1000.f);
  }
  {
    std::vector<std::uint8_t> u;
    for (float x : nv) u.push_back(std::uint8_t(int(x + 1000.f) % 256));
    const auto u8 = writeBytes(dir.path() / "u8.nrrd", nrrdHeader("uchar", narrow, spacings, "raw", "") + le(u));
    const VoxelVolume vol = readNrrd(u8, kAir);
    EXPECT_EQ(vol.valueAt(2, 3, 1), float(int(pattern(2, 3, 1) + 1000.f) % 256));
  }

  // Detached header (.nhdr) with the data in another file.
  writeBytes(dir.path() / "detached.raw", le(cast<float>(v)));
  std::string detached = nrrdHeader("float", d, spacings, "raw");
  detached.pop_back();  // no blank line: the header is the whole file
  const auto nhdr = dir.write("detached.nhdr", detached + "data file: detached.raw\n");
  expectPattern(readNrrd(nhdr, kAir), d, mm);
  const LoadedVolume loaded = loadVolume("detached.nhdr", dir.path(), kAir);
  EXPECT_EQ(loaded.format, "nrrd");
  expectPattern(loaded.volume, d, mm);
}

TEST(VolumeIONrrd, BadFiles) {
  ScratchDir dir;
  const glm::ivec3 d(11, 7, 5);
  const auto v = patternValues(d);
  const std::string data = le(cast<std::int16_t>(v));
  const std::string sp = "spacings: 0.5 0.25 2";
  auto nrrd = [&](const std::string& name, const std::string& header, const std::string& bytes) {
    return writeBytes(dir.path() / name, header + bytes);
  };

  const auto truncated = nrrd("truncated.nrrd", nrrdHeader("short", d, sp, "raw"), data.substr(0, data.size() - 100));
  EXPECT_VOLUME_ERROR(readNrrd(truncated, kAir), truncated, "truncated data: the header promises 770 bytes");
  EXPECT_VOLUME_ERROR(readNrrd(truncated, kAir), truncated, "the file has 670");
  const auto longer = nrrd("longer.nrrd", nrrdHeader("short", d, sp, "raw"), data + data);
  EXPECT_VOLUME_ERROR(readNrrd(longer, kAir), longer, "header/size mismatch");
  const auto gzCut = compress(data, 31);
  const auto gzTruncated = nrrd("gz_truncated.nrrd", nrrdHeader("short", d, sp, "gzip"), gzCut.substr(0, gzCut.size() / 2));
  EXPECT_VOLUME_ERROR(readNrrd(gzTruncated, kAir), gzTruncated, "truncated");
  const auto gzLong = nrrd("gz_long.nrrd", nrrdHeader("short", d, sp, "gzip"), compress(data + data, 31));
  EXPECT_VOLUME_ERROR(readNrrd(gzLong, kAir), gzLong, "header/size mismatch");
  const auto asciiShort = dir.write("ascii_short.nrrd", nrrdHeader("float", d, sp, "ascii", "") + "1 2 3\n");
  EXPECT_VOLUME_ERROR(readNrrd(asciiShort, kAir), asciiShort, "truncated data: the header promises 385 values");

  for (const auto& [name, spacing] : std::vector<std::pair<std::string, std::string>>{
           {"zero.nrrd", "spacings: 0.5 0 2"},
           {"negative.nrrd", "spacings: 0.5 0.25 -2"},
           {"nan.nrrd", "spacings: nan 0.25 2"},
           {"nan_direction.nrrd", "space directions: (0.5,0,0) (0,nan,0) (0,0,2)"}}) {
    const auto f = nrrd(name, nrrdHeader("short", d, spacing, "raw"), data);
    EXPECT_VOLUME_ERROR(readNrrd(f, kAir), f, "spacing along");
  }
  // Positive and finite, but no voxel: in metres where millimetres are read, or a kilometre.
  const auto metres = nrrd("metres.nrrd", nrrdHeader("short", d, "spacings: 0.0001 0.0001 0.0001", "raw"), data);
  EXPECT_VOLUME_ERROR(readNrrd(metres, kAir), metres, "voxel size 1e-07 m (0.0001 mm) along axis x is outside 1e-06 to 0.01 m");
  EXPECT_VOLUME_ERROR(readNrrd(metres, kAir), metres, "was it written in metres?");
  const auto kilometre = nrrd("kilometre.nrrd", nrrdHeader("short", d, "spacings: 0.1 0.1 1e6", "raw"), data);
  EXPECT_VOLUME_ERROR(readNrrd(kilometre, kAir), kilometre, "voxel size 1000 m (1e+06 mm) along axis z is outside");
  const auto noSpacing = nrrd("no_spacing.nrrd", nrrdHeader("short", d, "# no spacing", "raw"), data);
  EXPECT_VOLUME_ERROR(readNrrd(noSpacing, kAir), noSpacing, "voxel spacing is unknown");

  // Absurd dimensions fail on the header, before anything is allocated.
  const auto huge = nrrd("huge.nrrd", nrrdHeader("short", {100000, 100000, 100000}, sp, "raw"), data);
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_VOLUME_ERROR(readNrrd(huge, kAir), huge, "exceed the limit");
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(1));

  const auto bzip = nrrd("bzip.nrrd", nrrdHeader("short", d, sp, "bzip2"), data);
  EXPECT_VOLUME_ERROR(readNrrd(bzip, kAir), bzip, "unsupported NRRD encoding 'bzip2'");
  const auto block = nrrd("block.nrrd", nrrdHeader("block", d, sp, "raw"), data);
  EXPECT_VOLUME_ERROR(readNrrd(block, kAir), block, "unsupported NRRD type 'block'");
  const auto noEndian = nrrd("no_endian.nrrd", nrrdHeader("short", d, sp, "raw", ""), data);
  EXPECT_VOLUME_ERROR(readNrrd(noEndian, kAir), noEndian, "no 'endian' field");
  const auto vec = nrrd("vector.nrrd",
                        "NRRD0004\ntype: short\ndimension: 4\nsizes: 3 11 7 5\nkinds: vector domain domain domain\n"
                        "spacings: nan 0.5 0.25 2\nencoding: raw\nendian: little\n\n",
                        data + data + data);
  EXPECT_VOLUME_ERROR(readNrrd(vec, kAir), vec, "multi-component");
  const auto sizes = nrrd("sizes.nrrd", "NRRD0004\ntype: short\ndimension: 3\nsizes: 11 7\nspacings: 1 1 1\nencoding: raw\nendian: little\n\n", data);
  EXPECT_VOLUME_ERROR(readNrrd(sizes, kAir), sizes, "header/size mismatch");
  const auto notNrrd = dir.write("text.nrrd", "hello\n");
  EXPECT_VOLUME_ERROR(readNrrd(notNrrd, kAir), notNrrd, "not a NRRD file");
  EXPECT_VOLUME_ERROR(readNrrd(dir.path() / "missing.nrrd", kAir), dir.path() / "missing.nrrd", "no such file");
}

// ---- MetaImage ------------------------------------------------------------------

TEST(VolumeIOMetaImage, MhaAndMhdWithRaw) {
  ScratchDir dir;
  const glm::ivec3 d(11, 7, 5);
  const glm::dvec3 mm(0.5, 0.25, 2.0);
  const auto v = patternValues(d);

  const auto mha = writeBytes(dir.path() / "local.mha", mhaHeader("MET_SHORT", d, "0.5 0.25 2", "") + le(cast<std::int16_t>(v)));
  expectPattern(readMetaImage(mha, kAir), d, mm);

  writeBytes(dir.path() / "data.raw", be(cast<float>(v)));
  const auto mhd = dir.write("volume.mhd", mhaHeader("MET_FLOAT", d, "0.5 0.25 2", "", "data.raw", /*bigEndian=*/true));
  expectPattern(readMetaImage(mhd, kAir), d, mm);

  const std::string z = compress(le(cast<double>(v)), 15);
  const auto compressed = writeBytes(dir.path() / "compressed.mha",
                                     mhaHeader("MET_DOUBLE", d, "0.5 0.25 2",
                                               "CompressedData = True\nCompressedDataSize = " + std::to_string(z.size()) + "\n") +
                                         z);
  expectPattern(readMetaImage(compressed, kAir), d, mm);

  const glm::ivec3 narrow(3, 4, 2);
  const auto nv = patternValues(narrow);
  const auto small = writeBytes(dir.path() / "narrow.mha", mhaHeader("MET_INT", narrow, "1 1 1", "") + le(cast<std::int32_t>(nv)));
  expectPattern(readMetaImage(small, kAir), narrow, glm::dvec3(1.0));

  EXPECT_EQ(loadVolume("volume.mhd", dir.path(), kAir).format, "metaimage");
  EXPECT_EQ(loadVolume((dir.path() / "local.mha").string(), "/nonexistent", kAir).format, "metaimage");
}

TEST(VolumeIOMetaImage, BadFiles) {
  ScratchDir dir;
  const glm::ivec3 d(11, 7, 5);
  const std::string data = le(cast<std::int16_t>(patternValues(d)));
  auto mha = [&](const std::string& name, const std::string& header, const std::string& bytes) {
    return writeBytes(dir.path() / name, header + bytes);
  };
  const auto truncated = mha("truncated.mha", mhaHeader("MET_SHORT", d, "0.5 0.25 2", ""), data.substr(0, 500));
  EXPECT_VOLUME_ERROR(readMetaImage(truncated, kAir), truncated, "truncated data: the header promises 770 bytes");
  EXPECT_VOLUME_ERROR(readMetaImage(truncated, kAir), truncated, "the file has 500");
  const auto longer = mha("longer.mha", mhaHeader("MET_SHORT", d, "0.5 0.25 2", ""), data + "xx");
  EXPECT_VOLUME_ERROR(readMetaImage(longer, kAir), longer, "header/size mismatch");
  std::string header2 = mhaHeader("MET_SHORT", d, "0.5 0.25 2", "");
  header2.replace(header2.find("DimSize = 11 7 5"), 16, "DimSize = 11 7");
  const auto dims2 = mha("dims2.mha", header2, data);
  EXPECT_VOLUME_ERROR(readMetaImage(dims2, kAir), dims2, "header/size mismatch");
  const std::string z = compress(data, 15);
  const auto zCut = mha("z_cut.mha",
                        mhaHeader("MET_SHORT", d, "1 1 1", "CompressedData = True\nCompressedDataSize = " + std::to_string(z.size()) + "\n"),
                        z.substr(0, z.size() - 20));
  EXPECT_VOLUME_ERROR(readMetaImage(zCut, kAir), zCut, "truncated");
  const auto zBad = mha("z_bad.mha",
                        mhaHeader("MET_SHORT", d, "1 1 1", "CompressedData = True\nCompressedDataSize = " + std::to_string(z.size()) + "\n"),
                        std::string(z.size(), 'x'));
  EXPECT_VOLUME_ERROR(readMetaImage(zBad, kAir), zBad, "corrupt compressed data");

  for (const auto& [name, spacing] : std::vector<std::pair<std::string, std::string>>{
           {"zero.mha", "0.5 0 2"}, {"negative.mha", "0.5 -0.25 2"}, {"nan.mha", "0.5 0.25 nan"}}) {
    const auto f = mha(name, mhaHeader("MET_SHORT", d, spacing, ""), data);
    EXPECT_VOLUME_ERROR(readMetaImage(f, kAir), f, "spacing along");
  }
  const auto huge = mha("huge.mha", mhaHeader("MET_SHORT", {100000, 100000, 100000}, "1 1 1", ""), data);
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_VOLUME_ERROR(readMetaImage(huge, kAir), huge, "exceed the limit");
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(1));
  const auto channels = mha("channels.mha", mhaHeader("MET_SHORT", d, "1 1 1", "ElementNumberOfChannels = 3\n"), data + data + data);
  EXPECT_VOLUME_ERROR(readMetaImage(channels, kAir), channels, "multi-component");
  const auto type = mha("type.mha", mhaHeader("MET_STRING", d, "1 1 1", ""), data);
  EXPECT_VOLUME_ERROR(readMetaImage(type, kAir), type, "unsupported ElementType 'MET_STRING'");
  const auto missingRaw = dir.write("missing_raw.mhd", mhaHeader("MET_SHORT", d, "1 1 1", "", "nothere.raw"));
  EXPECT_VOLUME_ERROR(readMetaImage(missingRaw, kAir), missingRaw, "nothere.raw does not exist");
}

// ---- VTI --------------------------------------------------------------------------

TEST(VolumeIOVti, HandWrittenAscii) {
  ScratchDir dir;
  const glm::ivec3 d(11, 7, 5);
  const auto v = patternValues(d);
  const auto f = dir.write("volume.vti", vtiFile(d, "0.5 0.25 2", asciiValues(v)));
  expectPattern(readVti(f, kAir), d, glm::dvec3(0.5, 0.25, 2.0));
  const auto f2 = dir.write("float.vti", vtiFile(d, "1 1 1.5", asciiValues(v), "Float32"));
  const LoadedVolume loaded = loadVolume("float.vti", dir.path(), kAir);
  EXPECT_EQ(loaded.format, "vti");
  expectPattern(loaded.volume, d, glm::dvec3(1.0, 1.0, 1.5));
}

// The 1 MiB markup cap counts tags and comments, not inline array data: a
// file with 1.3 MB of inline values, a comment with an apostrophe and a '>'
// in a quoted attribute loads.
TEST(VolumeIOVti, MarkupCapLeavesInlineDataAlone) {
  ScratchDir dir;
  const glm::ivec3 d(400, 400, 4);
  const auto v = patternValues(d);
  std::string text = vtiFile(d, "0.5 0.25 2", asciiValues(v));
  ASSERT_GT(text.size(), std::size_t(1) << 20);
  text.insert(text.find("<ImageData"), "<!-- it's a \"test\" > -->\n");
  text.insert(text.find("byte_order="), "Note=\"a > b\" ");
  const auto f = dir.write("big.vti", text);
  expectPattern(readVti(f, kAir), d, glm::dvec3(0.5, 0.25, 2.0));
}

namespace {
// A .vti with the values as appended raw binary (UInt32 byte count, then little-endian int16).
std::string vtiAppended(glm::ivec3 d, const std::vector<float>& v) {
  const std::string data = le(cast<std::int16_t>(v));
  const std::uint32_t count = std::uint32_t(data.size());
  std::string header(4, '\0');
  std::memcpy(header.data(), &count, 4);
  std::ostringstream x;
  x << "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" "
       "header_type=\"UInt32\">\n<ImageData WholeExtent=\"0 "
    << d.x - 1 << " 0 " << d.y - 1 << " 0 " << d.z - 1 << "\" Origin=\"0 0 0\" Spacing=\"0.5 0.25 2\">\n<Piece Extent=\"0 "
    << d.x - 1 << " 0 " << d.y - 1 << " 0 " << d.z - 1
    << "\">\n<PointData Scalars=\"density\">\n<DataArray type=\"Int16\" Name=\"density\" format=\"appended\" "
       "offset=\"0\"/>\n</PointData>\n</Piece>\n</ImageData>\n<AppendedData encoding=\"raw\">\n_"
    << header << data << "\n</AppendedData>\n</VTKFile>\n";
  return x.str();
}
}  // namespace

TEST(VolumeIOVti, AppendedRaw) {
  ScratchDir dir;
  const glm::ivec3 d(11, 7, 5);
  const std::string file = vtiAppended(d, patternValues(d));
  const auto f = writeBytes(dir.path() / "appended.vti", file);
  expectPattern(readVti(f, kAir), d, glm::dvec3(0.5, 0.25, 2.0));
  // Cut inside the raw data: VTK alone would return garbage without an error.
  const auto cut = writeBytes(dir.path() / "cut.vti", file.substr(0, file.size() - 200));
  EXPECT_VOLUME_ERROR(readVti(cut, kAir), cut, "truncated");
}

TEST(VolumeIOVti, BadFiles) {
  ScratchDir dir;
  const glm::ivec3 d(11, 7, 5);
  const auto v = patternValues(d);
  const auto text = dir.write("text.vti", "this is not XML\n");
  EXPECT_VOLUME_ERROR(readVti(text, kAir), text, "not an XML file");
  const std::string good = vtiFile(d, "0.5 0.25 2", asciiValues(v));
  const auto cut = dir.write("cut.vti", good.substr(0, good.size() / 2));
  EXPECT_VOLUME_ERROR(readVti(cut, kAir), cut, "truncated");
  std::string broken = good;
  broken.replace(broken.find("<PointData"), 10, "<PointDat ");
  const auto badXml = dir.write("bad_xml.vti", broken);
  EXPECT_VOLUME_ERROR(readVti(badXml, kAir), badXml, "cannot read as VTK XML image data");
  const auto zero = dir.write("zero.vti", vtiFile(d, "0.5 0 2", asciiValues(v)));
  EXPECT_VOLUME_ERROR(readVti(zero, kAir), zero, "spacing along y");
  const auto negative = dir.write("negative.vti", vtiFile(d, "-0.5 1 2", asciiValues(v)));
  EXPECT_VOLUME_ERROR(readVti(negative, kAir), negative, "spacing along x");
  const auto huge = dir.write("huge.vti", vtiFile({100000, 100000, 100000}, "1 1 1", "1 2 3"));
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_VOLUME_ERROR(readVti(huge, kAir), huge, "exceed the limit");
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(1));
  const auto vec = dir.write("vector.vti", vtiFile(d, "1 1 1", asciiValues(v) + asciiValues(v) + asciiValues(v), "Int16", 3));
  EXPECT_VOLUME_ERROR(readVti(vec, kAir), vec, "multi-component");
}

// ---- OpenVDB and NRRD round trips ----------------------------------------------------

namespace {
VoxelVolume sampleVolume() {
  const glm::ivec3 d(19, 13, 9);
  std::vector<float> v;
  for (int k = 0; k < d.z; ++k)
    for (int j = 0; j < d.y; ++j)
      for (int i = 0; i < d.x; ++i) {
        const double r = std::hypot(i - 9.0, j - 6.0, (k - 4.0) * 1.5);
        v.push_back(r < 5.5 ? float(1600.0 + 37.25 * i - 11.5 * j + k * 0.125) : -1000.f);  // a ball in air
      }
  return VoxelVolume::fromDense(v.data(), d, glm::dvec3(0.1e-3, 0.125e-3, 0.3e-3), -1000.f);
}

void expectSame(const VoxelVolume& a, const VoxelVolume& b) {
  ASSERT_EQ(a.dims(), b.dims());
  for (int i = 0; i < 3; ++i) EXPECT_DOUBLE_EQ(a.voxelSize()[i], b.voxelSize()[i]);
  EXPECT_EQ(a.activeVoxels(), b.activeVoxels());
  EXPECT_EQ(a.contentHash(), b.contentHash());
}
}  // namespace

TEST(VolumeIORoundTrip, VdbAndNrrd) {
  ScratchDir dir;
  const VoxelVolume original = sampleVolume();
  ASSERT_GT(original.activeVoxels(), 100u);

  writeVdb(original, dir.path() / "v.vdb");
  expectSame(readVdb(dir.path() / "v.vdb", -1000.f), original);
  writeNrrd(original, dir.path() / "raw.nrrd", false);
  expectSame(readNrrd(dir.path() / "raw.nrrd", -1000.f), original);
  writeNrrd(original, dir.path() / "gz.nrrd", true);
  expectSame(readNrrd(dir.path() / "gz.nrrd", -1000.f), original);
  EXPECT_LT(fs::file_size(dir.path() / "gz.nrrd"), fs::file_size(dir.path() / "raw.nrrd"));

  const LoadedVolume l1 = loadVolume("v.vdb", dir.path(), -1000.f);
  EXPECT_EQ(l1.format, "vdb");
  expectSame(l1.volume, original);
  fs::copy_file(dir.path() / "gz.nrrd", dir.path() / "upper.NRRD");
  const LoadedVolume l2 = loadVolume("upper.NRRD", dir.path(), -1000.f);  // the extension's case does not matter
  EXPECT_EQ(l2.format, "nrrd");
}

TEST(VolumeIOVdb, DimsFromActiveVoxelsWithoutMetadataAndBadFiles) {
  ScratchDir dir;
  openvdb::initialize();
  auto grid = openvdb::FloatGrid::create(0.f);
  grid->setName("other");
  grid->tree().setValue(openvdb::Coord(6, 3, 2), 5.f);
  grid->tree().setValue(openvdb::Coord(0, 0, 0), 2.f);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(0.25));
  auto intGrid = openvdb::Int32Grid::create(0);
  intGrid->setName("density");  // not a float grid: skipped
  {
    openvdb::io::File f((dir.path() / "plain.vdb").string());
    f.write(openvdb::GridPtrVec{intGrid, grid});
    f.close();
  }
  const VoxelVolume vol = readVdb(dir.path() / "plain.vdb", 0.f);
  EXPECT_EQ(vol.dims(), glm::ivec3(7, 4, 3));
  EXPECT_DOUBLE_EQ(vol.voxelSize().x, 0.25e-3);
  EXPECT_EQ(vol.valueAt(6, 3, 2), 5.f);
  EXPECT_EQ(vol.valueAt(0, 0, 0), 2.f);

  {
    openvdb::io::File f((dir.path() / "ints.vdb").string());
    f.write(openvdb::GridPtrVec{intGrid});
    f.close();
  }
  EXPECT_VOLUME_ERROR(readVdb(dir.path() / "ints.vdb", 0.f), dir.path() / "ints.vdb", "no float grid");
  const auto text = dir.write("text.vdb", "not a vdb file\n");
  EXPECT_VOLUME_ERROR(readVdb(text, 0.f), text, "cannot read as an OpenVDB file");
  writeVdb(sampleVolume(), dir.path() / "ok.vdb");
  const std::string bytes = readBytes(dir.path() / "ok.vdb");
  const auto cut = writeBytes(dir.path() / "cut.vdb", bytes.substr(0, bytes.size() / 2));
  EXPECT_VOLUME_ERROR(readVdb(cut, -1000.f), cut, "cut.vdb: ");
}

// A grid whose statistics (written by OpenVDB with every grid) say it spans
// more voxels than a volume may have is refused before its tree is read.
TEST(VolumeIOVdb, RefusesAGridTooLargeFromItsStatistics) {
  ScratchDir dir;
  openvdb::initialize();
  auto grid = openvdb::FloatGrid::create(0.f);
  grid->setName("density");
  // One active 8³ tile at each end of a 3976³ box: a tiny file and tree.
  grid->tree().addTile(1, openvdb::Coord(0), 1.f, true);
  grid->tree().addTile(1, openvdb::Coord(4095 - 127), 1.f, true);
  {
    openvdb::io::File f((dir.path() / "huge.vdb").string());
    f.write(openvdb::GridPtrVec{grid});
    f.close();
  }
  EXPECT_VOLUME_ERROR(readVdb(dir.path() / "huge.vdb", 0.f), dir.path() / "huge.vdb",
                      "grid 'density' spans [0, 0, 0] to [3975, 3975, 3975], more than the limit of 1073741824 voxels");
}

// A corrupt length or count in a .vdb's metadata is refused before OpenVDB
// reads it: trusting a 4 GB name length, OpenVDB allocated it and looped over
// garbage entries past the end of the file (11.7 GB resident, then killed;
// found by mutating a small .vdb). Each case here is a real file written by
// writeVdb with one field changed, and must fail fast with the field named.
TEST(VolumeIOVdb, CorruptLengthsAndCountsAreRefusedBeforeOpenVdbReadsThem) {
  ScratchDir dir;
  writeVdb(sampleVolume(), dir.path() / "ok.vdb");
  const std::string good = readBytes(dir.path() / "ok.vdb");
  ASSERT_NO_THROW(readVdb(dir.path() / "ok.vdb", -1000.f));
  // The offsets of the fields, found in the file as writeVdb lays it out.
  const std::size_t gridName = good.find("density") - 4;       // the first descriptor's name length
  const std::size_t metaName = good.find("file_bbox_max") - 4;  // the grid's first metadata name length
  ASSERT_NE(good.find("density"), std::string::npos);
  ASSERT_NE(good.find("file_bbox_max"), std::string::npos);
  auto with = [&](const char* name, std::size_t at, std::uint32_t value) {
    std::string bytes = good;
    std::memcpy(bytes.data() + at, &value, sizeof value);
    return writeBytes(dir.path() / name, bytes);
  };
  const auto longName = with("long_name.vdb", metaName, 0xff000004u);
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_VOLUME_ERROR(readVdb(longName, -1000.f), longName,
                      "corrupt OpenVDB file: the metadata name has the length 4278190084 at byte");
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(2));
  const auto pastEnd = with("past_end.vdb", metaName, 100000);
  EXPECT_VOLUME_ERROR(readVdb(pastEnd, -1000.f), pastEnd, "the metadata name at byte");
  const auto manyEntries = with("many_entries.vdb", metaName - 4, 0x7fffffff);
  EXPECT_VOLUME_ERROR(readVdb(manyEntries, -1000.f), manyEntries, "the grid metadata count is 2147483647 at byte");
  const auto manyGrids = with("many_grids.vdb", gridName - 4, 0x10000000);
  EXPECT_VOLUME_ERROR(readVdb(manyGrids, -1000.f), manyGrids, "the grid count is 268435456");
  const auto cut = writeBytes(dir.path() / "cut.vdb", good.substr(0, metaName + 40));
  EXPECT_VOLUME_ERROR(readVdb(cut, -1000.f), cut, "past the end of the file");
}

// OpenVDB 10 reads a chunk marked "stored uncompressed" into its buffer
// before it checks the chunk's size (io/Compression.cc): this file (the 16 ×
// 16 × 12 phantom written by `millsim phantom`, two bytes of a chunk size
// changed by the mutation fuzzing that found it) made it write past a heap
// buffer, and millsim crashed at exit after printing the error. readVdb reads
// a file in a child process first, so this process never runs that read: the
// child's error comes up (or, where the child itself stops on the overflow,
// as under AddressSanitizer, that it stopped), and nothing here is overwritten.
TEST(VolumeIOVdb, AChunkThatWouldOverflowOpenVdbsBufferIsRefusedWithoutReadingItHere) {
  const fs::path file = fs::path(MILLSIM_SOURCE_DIR) / "tests/data/vdb/uncompressed-chunk-overflow.vdb";
  ASSERT_TRUE(fs::exists(file));
  const std::string message = errorOf([&] { (void)readVdb(file, -1000.f); });
  std::cout << message << "\n";
  EXPECT_EQ(message.rfind(file.string(), 0), 0u) << message;
  EXPECT_TRUE(message.find("Expected to read a 168-byte uncompressed chunk") != std::string::npos ||
              message.find("OpenVDB's reader") != std::string::npos)
      << message;
  // And a good file still reads, after its check in the child.
  ScratchDir dir;
  writeVdb(sampleVolume(), dir.path() / "ok.vdb");
  expectSame(readVdb(dir.path() / "ok.vdb", -1000.f), sampleVolume());
}

// The probe that reads a .vdb first is a process of its own, not a fork of
// this one: a fork inherits whatever TBB's workers (busy here on another
// thread's parallel loop, as OpenVDB's own are after any tree operation) held
// at that instant, and a forked child that then ran OpenVDB's parallel tree
// code waited a minute on CI. Twenty reads of a file of many leaves while TBB
// is busy all finish, each well inside the probe's wall-clock limit.
TEST(VolumeIOVdb, AReadWhileTbbIsBusyOnAnotherThreadFinishes) {
  ScratchDir dir;
  openvdb::initialize();
  auto grid = openvdb::FloatGrid::create(-1000.f);
  grid->setName("density");
  for (int i = 0; i < 64; i += 2)
    for (int j = 0; j < 64; j += 3)
      for (int k = 0; k < 64; k += 5) grid->tree().setValue(openvdb::Coord(i, j, k), float(i + j + k));
  grid->setTransform(openvdb::math::Transform::createLinearTransform(0.1));
  {
    openvdb::io::File f((dir.path() / "leaves.vdb").string());
    f.write(openvdb::GridPtrVec{grid});
    f.close();
  }
  std::atomic<bool> stop{false};
  std::thread busy([&] {
    while (!stop.load()) {
      auto copy = grid->deepCopy();  // OpenVDB's parallel copy, then its parallel clear
      openvdb::tools::pruneInactive(copy->tree());
    }
  });
  for (int n = 0; n < 20; ++n) {
    const auto start = std::chrono::steady_clock::now();
    const VoxelVolume v = readVdb(dir.path() / "leaves.vdb", -1000.f);
    EXPECT_EQ(v.valueAt(62, 63, 60), 185.f);
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(30)) << "read " << n;
  }
  stop.store(true);
  busy.join();
}

// Without its probe readVdb reads no file, and says where it looked.
TEST(VolumeIOVdb, AMissingProbeIsAClearError) {
  ScratchDir dir;
  writeVdb(sampleVolume(), dir.path() / "ok.vdb");
  const fs::path missing = dir.path() / "no-such-probe";
  setenv("MILLSIM_VDB_PROBE", missing.c_str(), 1);
  const std::string message = errorOf([&] { (void)readVdb(dir.path() / "ok.vdb", -1000.f); });
  unsetenv("MILLSIM_VDB_PROBE");
  EXPECT_NE(message.find("millsim-vdb-probe is not at " + missing.string()), std::string::npos) << message;
  EXPECT_NE(message.find("set MILLSIM_VDB_PROBE"), std::string::npos) << message;
  // A probe that cannot start (its libraries missing: the loader exits 127) is
  // not a corrupt file.
  const fs::path broken = dir.write("broken-probe", "#!/bin/sh\nexit 127\n");
  fs::permissions(broken, fs::perms::owner_all);
  setenv("MILLSIM_VDB_PROBE", broken.c_str(), 1);
  const std::string cannotStart = errorOf([&] { (void)readVdb(dir.path() / "ok.vdb", -1000.f); });
  unsetenv("MILLSIM_VDB_PROBE");
  EXPECT_NE(cannotStart.find("could not start (status 127"), std::string::npos) << cannotStart;
  EXPECT_EQ(cannotStart.find("corrupt"), std::string::npos) << cannotStart;
  expectSame(readVdb(dir.path() / "ok.vdb", -1000.f), sampleVolume());
}

// readVdb copies the file's tree tile by tile and leaf by leaf, never dense.
// What it must give is what a dense copy means: every voxel of the box takes
// its value if active, the file's background if not, and values at or below
// air become inactive air. Checked against exactly that, built voxel by
// voxel, through fromDense; with tiles of two levels cut by the box, inactive
// voxels holding other values, active voxels outside the box (one NaN), a box
// that is no multiple of 8, and a background that is air and one that is not.
TEST(VolumeIOVdb, TheSparseCopyIsWhatADenseCopyMeans) {
  ScratchDir dir;
  openvdb::initialize();
  const float air = -1000.f;
  const glm::ivec3 dims(21, 19, 140);
  for (const float background : {-1000.f, -2000.f, 300.f}) {
    auto grid = openvdb::FloatGrid::create(background);
    grid->setName("density");
    auto& tree = grid->tree();
    tree.addTile(1, openvdb::Coord(8, 8, 0), 900.f, true);     // an 8³ tile inside the box
    tree.addTile(1, openvdb::Coord(16, 16, 8), 500.f, true);   // cut by x = 20 and y = 18
    tree.addTile(1, openvdb::Coord(0, 8, 16), -1500.f, true);  // active, below air
    tree.addTile(2, openvdb::Coord(0, 0, 128), 700.f, true);   // a 128³ tile cut to 12 slices
    tree.addTile(1, openvdb::Coord(0, 0, 24), 40.f, false);    // inactive: the background
    for (int i = 0; i < 21; ++i)
      for (int k = 30; k < 50; ++k) tree.setValue(openvdb::Coord(i, (i * 7 + k) % 19, k), float(10 * i - 1100 + k));
    tree.setValueOff(openvdb::Coord(3, 3, 3), 800.f);  // an inactive voxel in a leaf
    tree.setValue(openvdb::Coord(4, 3, 3), -1000.f);    // exactly air
    tree.setValue(openvdb::Coord(-1, 2, 2), 600.f);     // outside the box
    tree.setValue(openvdb::Coord(5, 19, 2), std::nanf(""));
    grid->insertMeta("millsim_dims", openvdb::Vec3IMetadata(openvdb::Vec3i(dims.x, dims.y, dims.z)));
    grid->setTransform(openvdb::math::Transform::createLinearTransform(0.1));
    const auto file = dir.path() / "sparse.vdb";
    {
      openvdb::io::File f(file.string());
      f.write(openvdb::GridPtrVec{grid});
      f.close();
    }
    std::vector<float> dense;
    auto acc = grid->getConstAccessor();
    for (int k = 0; k < dims.z; ++k)
      for (int j = 0; j < dims.y; ++j)
        for (int i = 0; i < dims.x; ++i) {
          const openvdb::Coord c(i, j, k);
          dense.push_back(acc.isValueOn(c) ? acc.getValue(c) : background);
        }
    const VoxelVolume expected = VoxelVolume::fromDense(dense.data(), dims, glm::dvec3(0.1e-3), air);
    const VoxelVolume read = readVdb(file, air);
    SCOPED_TRACE("background " + std::to_string(background));
    expectSame(read, expected);
    EXPECT_EQ(read.grid().tree().leafCount(), expected.grid().tree().leafCount());
    EXPECT_EQ(read.memoryBytes(), expected.memoryBytes());
    EXPECT_EQ(read.grid().tree().activeTileCount(), 0u) << "material in tiles: milling would allocate";
  }
}

// A density that is not a number (or is infinite) is refused with the voxel
// that holds it, whichever reader read it: compared with air, a NaN is not
// air, so it stayed material and made the field near it NaN.
TEST(VolumeIONonFinite, EveryReaderRefusesADensityThatIsNotFinite) {
  ScratchDir dir;
  openvdb::initialize();
  const glm::ivec3 d(3, 2, 2);
  const auto nanNrrd = dir.write("nan.nrrd", nrrdHeader("float", d, "spacings: 0.1 0.1 0.1", "ascii", "") +
                                                 "1 2 3 4 5 6 7 nan 9 10 11 12\n");
  EXPECT_VOLUME_ERROR(readNrrd(nanNrrd, kAir), nanNrrd, "voxel (1, 0, 1) has the density nan");
  const auto infNrrd = dir.write("inf.nrrd", nrrdHeader("float", d, "spacings: 0.1 0.1 0.1", "ascii", "") +
                                                 "1 2 3 4 5 -inf 7 8 9 10 11 12\n");
  EXPECT_VOLUME_ERROR(readNrrd(infNrrd, kAir), infNrrd, "voxel (2, 1, 0) has the density -inf");
  // Read a slab of eight slices at a time, so the NaN in the first slab of a gzip stream is refused mid-stream:
  // zlib's state must be ended on that way out too (LeakSanitizer found it left, Dec 2026).
  const glm::ivec3 tall(4, 4, 20);
  std::vector<float> values(std::size_t(tall.x) * tall.y * tall.z, 1.f);
  values[(std::size_t(3) * tall.y + 2) * tall.x + 1] = std::nanf("");
  const auto nanGzip = writeBytes(dir.path() / "nan-gzip.nrrd", nrrdHeader("float", tall, "spacings: 0.1 0.1 0.1", "gzip") +
                                                                    compress(le(values), 31));
  EXPECT_VOLUME_ERROR(readNrrd(nanGzip, kAir), nanGzip, "voxel (1, 2, 3) has the density nan");
  const auto nanMha = writeBytes(dir.path() / "nan.mha", mhaHeader("MET_FLOAT", tall, "0.1 0.1 0.1", "") + le(values));
  EXPECT_VOLUME_ERROR(readMetaImage(nanMha, kAir), nanMha, "voxel (1, 2, 3) has the density nan");
  const auto infVti = dir.write("inf.vti", vtiFile(d, "0.1 0.1 0.1", "1 2 3 4 5 6 7 8 9 10 inf 12", "Float32"));
  EXPECT_VOLUME_ERROR(readVti(infVti, kAir), infVti, "voxel (1, 1, 1) has the density inf");

  auto grid = openvdb::FloatGrid::create(0.f);
  grid->setName("density");
  grid->tree().setValue(openvdb::Coord(0, 0, 0), 5.f);
  grid->tree().setValue(openvdb::Coord(2, 1, 3), std::numeric_limits<float>::infinity());
  const auto write = [&](const char* name) {
    const auto f = dir.path() / name;
    openvdb::io::File out(f.string());
    out.write(openvdb::GridPtrVec{grid});
    out.close();
    return f;
  };
  const auto infVdb = write("inf.vdb");
  EXPECT_VOLUME_ERROR(readVdb(infVdb, 0.f), infVdb, "voxel (2, 1, 3) has the density inf");
  grid->tree().setValue(openvdb::Coord(2, 1, 3), 1.f);
  grid->tree().addTile(1, openvdb::Coord(8, 0, 0), std::nanf(""), true);
  const auto nanTile = write("nan_tile.vdb");
  EXPECT_VOLUME_ERROR(readVdb(nanTile, 0.f), nanTile, "voxel (8, 0, 0) has the density nan");
  auto nanBackground = openvdb::FloatGrid::create(std::nanf(""));
  nanBackground->setName("density");
  nanBackground->tree().setValue(openvdb::Coord(1, 1, 1), 5.f);
  grid = nanBackground;
  const auto nanBg = write("nan_background.vdb");
  EXPECT_VOLUME_ERROR(readVdb(nanBg, 0.f), nanBg, "has the background value nan");
}

// ---- loadVolume ------------------------------------------------------------------------

TEST(VolumeIOLoad, DispatchAndRefusals) {
  ScratchDir dir;
  EXPECT_VOLUME_ERROR(loadVolume("nothere.nrrd", dir.path(), kAir), dir.path() / "nothere.nrrd", "no such file");
  const auto odd = dir.write("volume.xyz", "data");
  const std::string msg = errorOf([&] { loadVolume("volume.xyz", dir.path(), kAir); });
  EXPECT_EQ(msg.rfind(odd.string(), 0), 0u) << msg;
  EXPECT_NE(msg.find("unknown volume file extension '.xyz'"), std::string::npos) << msg;
  for (const char* ext : {".vdb", ".nrrd", ".nhdr", ".mha", ".mhd", ".vti", ".dcm"})
    EXPECT_NE(msg.find(ext), std::string::npos) << "the message should list " << ext << ": " << msg;
  EXPECT_VOLUME_ERROR(loadVolume("http://example.com/ct.nrrd", dir.path(), kAir), "http://example.com/ct.nrrd",
                      "'http:' urls are not supported");
  EXPECT_VOLUME_ERROR(loadVolume("", dir.path(), kAir), "", "no volume file given");

  // file: urls and extension-less DICOM slices.
  fs::copy_file(kPydicomFiles / "CT_small.dcm", dir.path() / "IM0001");
  EXPECT_EQ(loadVolume("file://" + (dir.path() / "IM0001").string(), "", kAir).format, "dicom");
}

TEST(VolumeIOLoad, Phantom) {
  const LoadedVolume p = loadVolume("phantom:tooth?size=24,24,16", "/nonexistent", -1000.f);
  EXPECT_EQ(p.format, "phantom");
  EXPECT_EQ(p.source, "phantom:tooth?size=24,24,16");
  EXPECT_EQ(p.volume.dims(), glm::ivec3(24, 24, 16));
  EXPECT_GT(p.volume.activeVoxels(), 0u);
}
