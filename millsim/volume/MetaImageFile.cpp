// MetaImage files (.mha with the data after the header, .mhd with a separate data file): readMetaImage.
//
// The data is read by VTK's vtkMetaImageReader (MetaIO). MetaIO is lenient in
// ways that would hide broken files (checked with VTK 9.1 on Debian 12): it
// reports truncated or undecompressable data only on stderr and returns the
// image anyway (zeros or garbage, error code 0), and it takes the absolute
// value of negative spacings. So the header is parsed and checked here first
// (sizes before any allocation, spacing, components, type, file size, and a
// full zlib check of compressed data), and VTK's output is checked after.
#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkExecutive.h>
#include <vtkImageData.h>
#include <vtkMetaImageReader.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkType.h>
#include <zlib.h>

#include "millsim/volume/ReaderLimits.h"
#include "millsim/volume/MedicalModule.h"
#include "millsim/volume/VolumeBuilder.h"
#include "millsim/volume/VolumeIO.h"
#include "millsim/volume/VtkReading.h"

namespace fs = std::filesystem;

namespace millsim {

namespace {

using vtkio::appendFloats;
using vtkio::VtkMessages;

struct MetaType {
  const char* name;
  int bytes;
};
const std::map<std::string, MetaType>& metaTypes() {
  static const std::map<std::string, MetaType> m = {
      {"MET_CHAR", {"int8", 1}},       {"MET_UCHAR", {"uint8", 1}},      {"MET_SHORT", {"int16", 2}},
      {"MET_USHORT", {"uint16", 2}},   {"MET_INT", {"int32", 4}},        {"MET_UINT", {"uint32", 4}},
      {"MET_LONG_LONG", {"int64", 8}}, {"MET_ULONG_LONG", {"uint64", 8}}, {"MET_FLOAT", {"float", 4}},
      {"MET_DOUBLE", {"double", 8}},
  };
  return m;
}

bool isTrue(const std::string& v) {
  const std::string l = asciiLower(v);
  return l == "true" || l == "1" || l == "yes";
}

// Inflates a zlib/gzip stream without keeping it, to learn whether it holds exactly `want` bytes.
std::string checkCompressed(std::ifstream& in, std::uintmax_t compressedBytes, std::uintmax_t want) {
  z_stream zs{};
  if (inflateInit2(&zs, 15 + 32) != Z_OK) return "cannot start zlib";
  std::vector<unsigned char> chunk(1 << 18), out(1 << 18);
  std::uintmax_t left = compressedBytes, produced = 0;
  std::string error;
  bool end = false;
  while (!end && error.empty()) {
    if (zs.avail_in == 0 && left > 0) {
      const std::size_t k = std::size_t(std::min<std::uintmax_t>(left, chunk.size()));
      in.read(reinterpret_cast<char*>(chunk.data()), std::streamsize(k));
      zs.next_in = chunk.data();
      zs.avail_in = uInt(in.gcount());
      left = zs.avail_in == 0 ? 0 : left - zs.avail_in;
    }
    zs.next_out = out.data();
    zs.avail_out = uInt(out.size());
    const int rc = inflate(&zs, Z_NO_FLUSH);
    produced += out.size() - zs.avail_out;
    if (produced > want)
      error = "header/size mismatch: the compressed data holds more than the " + std::to_string(want) +
              " bytes the header promises";
    else if (rc == Z_STREAM_END)
      end = true;
    else if (rc == Z_DATA_ERROR || rc == Z_MEM_ERROR || rc == Z_NEED_DICT)
      error = std::string("corrupt compressed data (") + (zs.msg ? zs.msg : "zlib error") + ")";
    else if (rc == Z_BUF_ERROR && left == 0 && zs.avail_in == 0)
      error = "truncated data: the compressed stream ends early; the header promises " + std::to_string(want) +
              " bytes, it holds " + std::to_string(produced);
  }
  inflateEnd(&zs);
  if (error.empty() && produced < want)
    error = "truncated data: the header promises " + std::to_string(want) + " bytes, the compressed data holds " +
            std::to_string(produced);
  return error;
}

}  // namespace

VoxelVolume medical::readMetaImage(const fs::path& file, float airValue) {
  const std::string name = file.string();
  requireFile(file, "a MetaImage file");

  // --- Header: "Key = Value" lines; ElementDataFile is the last one.
  std::ifstream in(file, std::ios::binary);
  if (!in) throw VolumeError(name + ": cannot open the file");
  std::map<std::string, std::string> f;  // lower-cased keys
  bool sawDataFile = false;
  // Capped: a header that never ends, or one endless line, stops at kMaxHeaderBytes.
  HeaderLines lines(in, name, "MetaImage", "an ElementDataFile line");
  for (std::string line; lines.next(line);) {
    const std::size_t eq = line.find('=');
    if (eq == std::string::npos) {
      if (trim(line).empty()) continue;
      throw VolumeError(name + ": not a MetaImage header: line '" + line.substr(0, 60) + "' is not 'Key = Value'");
    }
    const std::string key = asciiLower(trim(line.substr(0, eq)));
    f[key] = trim(line.substr(eq + 1));
    if (key == "elementdatafile") {
      sawDataFile = true;
      break;
    }
  }
  if (!sawDataFile) throw VolumeError(name + ": not a MetaImage file (no ElementDataFile line ends the header)");
  auto get = [&](const char* k) -> std::string {
    auto it = f.find(k);
    return it == f.end() ? std::string() : it->second;
  };

  if (!get("objecttype").empty() && asciiLower(get("objecttype")) != "image")
    throw VolumeError(name + ": ObjectType is '" + get("objecttype") + "', not Image");
  if (get("ndims") != "3") {
    if (get("ndims").empty()) throw VolumeError(name + ": the MetaImage header has no NDims");
    throw VolumeError(name + ": NDims = " + get("ndims") + ": only 3-D volumes are supported");
  }
  const std::string channels = get("elementnumberofchannels");
  if (!channels.empty() && channels != "1")
    throw VolumeError(name + ": ElementNumberOfChannels = " + channels +
                      ": multi-component data is not supported (one value per voxel)");

  const auto dimWords = words(get("dimsize"));
  if (dimWords.size() != 3)
    throw VolumeError(name + ": header/size mismatch: DimSize '" + get("dimsize") + "' must give 3 sizes for NDims = 3");
  glm::ivec3 dims;
  for (int a = 0; a < 3; ++a) {
    char* end = nullptr;
    const long long v = std::strtoll(dimWords[a].c_str(), &end, 10);
    if (*end != '\0' || v < 1) throw VolumeError(name + ": DimSize '" + get("dimsize") + "' must be positive integers");
    if (v > INT_MAX) throw VolumeError(name + ": DimSize " + dimWords[a] + " is too large for a volume");
    dims[a] = int(v);
  }

  std::string spacingKey = "elementspacing";
  if (get(spacingKey.c_str()).empty()) spacingKey = "elementsize";
  const auto spWords = words(get(spacingKey.c_str()));
  if (spWords.empty()) throw VolumeError(name + ": no ElementSpacing: the voxel spacing is unknown");
  if (spWords.size() != 3)
    throw VolumeError(name + ": header/size mismatch: ElementSpacing '" + get(spacingKey.c_str()) +
                      "' must give 3 numbers");
  glm::dvec3 mm;
  for (int a = 0; a < 3; ++a) {
    char* end = nullptr;
    mm[a] = std::strtod(spWords[a].c_str(), &end);
    if (*end != '\0') throw VolumeError(name + ": ElementSpacing '" + spWords[a] + "' is not a number");
    if (!std::isfinite(mm[a]) || mm[a] <= 0.0)
      throw VolumeError(name + ": spacing along " + "xyz"[a] + " is " + fmt(mm[a]) +
                        " mm; spacing must be a positive finite number of millimetres");
  }
  const glm::dvec3 spacing = mm / 1000.0;
  checkVolumeShape(name, dims, spacing);  // before anything is allocated

  const std::string typeName = get("elementtype");
  const auto type = metaTypes().find(typeName);
  if (type == metaTypes().end())
    throw VolumeError(name + ": unsupported ElementType '" + typeName +
                      "' (supported: MET_CHAR, MET_UCHAR, MET_SHORT, MET_USHORT, MET_INT, MET_UINT, MET_FLOAT, MET_DOUBLE)");
  if (!get("binarydata").empty() && !isTrue(get("binarydata")))
    throw VolumeError(name + ": BinaryData = False (text data) is not supported");

  // --- Data size, before VTK reads anything.
  const std::string dataFile = get("elementdatafile");
  const auto dataWords = words(dataFile);
  if (dataWords.size() != 1 || dataFile.rfind("LIST", 0) == 0 || dataFile.find('%') != std::string::npos)
    throw VolumeError(name + ": data split over several files (ElementDataFile = " + dataFile + ") is not supported");
  const bool local = dataFile == "LOCAL" || dataFile == "Local" || dataFile == "local";
  const fs::path dataPath = local ? file : (fs::path(dataFile).is_absolute() ? fs::path(dataFile) : file.parent_path() / dataFile);
  std::error_code ec;
  if (!fs::is_regular_file(dataPath, ec)) throw VolumeError(name + ": data file " + dataPath.string() + " does not exist");
  const std::uintmax_t size = fs::file_size(dataPath, ec);
  if (ec) throw VolumeError(name + ": cannot read the size of " + dataPath.string());
  const std::string where = local ? "the file" : "data file " + dataPath.string();
  const std::size_t n = std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z);
  const std::uintmax_t want = std::uintmax_t(n) * std::uintmax_t(type->second.bytes);
  const std::string promise = std::to_string(want) + " bytes (" + std::to_string(dims.x) + "x" +
                              std::to_string(dims.y) + "x" + std::to_string(dims.z) + " " + type->second.name + ")";
  long long headerSize = 0;
  if (!get("headersize").empty()) headerSize = std::strtoll(get("headersize").c_str(), nullptr, 10);
  const bool compressed = isTrue(get("compresseddata"));
  std::uintmax_t offset = local ? lines.consumed() : 0;
  if (!local && headerSize > 0) offset = std::uintmax_t(headerSize);
  if (!local && headerSize == -1 && !compressed) offset = size >= want ? size - want : 0;
  const std::uintmax_t available = size > offset ? size - offset : 0;

  if (!compressed) {
    if (available < want)
      throw VolumeError(name + ": truncated data: the header promises " + promise + ", " + where + " has " +
                        std::to_string(available));
    if (available > want)
      throw VolumeError(name + ": header/size mismatch: the header promises " + promise + ", " + where + " has " +
                        std::to_string(available));
  } else {
    std::uintmax_t compressedBytes = available;
    if (!get("compresseddatasize").empty()) {
      compressedBytes = std::uintmax_t(std::strtoull(get("compresseddatasize").c_str(), nullptr, 10));
      if (compressedBytes > available)
        throw VolumeError(name + ": truncated data: CompressedDataSize is " + std::to_string(compressedBytes) +
                          " bytes, " + where + " has " + std::to_string(available));
    } else if (local) {
      // MetaIO cannot find the end of LOCAL compressed data without it (it fails to decompress).
      throw VolumeError(name + ": CompressedData = True with LOCAL data needs a CompressedDataSize field");
    }
    // Refused before inflating anything when deflate cannot expand that far (ReaderLimits.h).
    if (deflateCannotHold(compressedBytes, want))
      throw VolumeError(name + ": truncated data: the header promises " + promise + ", but " + where + " holds only " +
                        std::to_string(compressedBytes) + " compressed bytes, which zlib cannot expand that far");
    std::ifstream data(dataPath, std::ios::binary);
    data.seekg(std::streamoff(offset));
    const std::string error = checkCompressed(data, compressedBytes, want);
    if (!error.empty()) throw VolumeError(name + ": " + error);
  }

  // --- VTK reads the data.
  VtkMessages messages;  // outlives the reader, which holds its callback
  vtkNew<vtkMetaImageReader> reader;
  messages.watch(reader);
  reader->SetFileName(name.c_str());
  reader->Update();
  if (!messages.text.empty()) throw VolumeError(name + ": " + messages.text);
  vtkImageData* image = reader->GetOutput();
  int d[3] = {0, 0, 0};
  if (image) image->GetDimensions(d);
  vtkDataArray* scalars = image ? image->GetPointData()->GetScalars() : nullptr;
  if (!scalars || d[0] != dims.x || d[1] != dims.y || d[2] != dims.z)
    throw VolumeError(name + ": VTK could not read the MetaImage data (got " + std::to_string(d[0]) + "x" +
                      std::to_string(d[1]) + "x" + std::to_string(d[2]) + ", expected " + std::to_string(dims.x) + "x" +
                      std::to_string(dims.y) + "x" + std::to_string(dims.z) + ")");
  if (scalars->GetNumberOfComponents() != 1)
    throw VolumeError(name + ": " + std::to_string(scalars->GetNumberOfComponents()) +
                      " components per voxel: multi-component data is not supported");
  if (std::size_t(scalars->GetNumberOfTuples()) != n)
    throw VolumeError(name + ": VTK read " + std::to_string(scalars->GetNumberOfTuples()) + " values, expected " +
                      std::to_string(n));
  VolumeBuilder volume(dims, spacing, airValue, name);
  try {
    appendFloats(scalars, volume);
  } catch (const std::runtime_error& e) {
    throw VolumeError(name + ": " + e.what());
  }
  return volume.finish();
}

}  // namespace millsim
