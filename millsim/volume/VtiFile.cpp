// VTK XML image data (.vti): readVti, through vtkXMLImageDataReader.
//
// The reader's information pass (extent, spacing, arrays) runs first, so the
// size is checked before VTK allocates the data. VTK's errors are caught with
// an observer and put into the exception instead of being printed.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkDataObject.h>
#include <vtkExecutive.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkType.h>
#include <vtkXMLImageDataReader.h>

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

// VTK's XML parser keeps every element and attribute in memory, so a file
// whose markup never ends (a 1 GB attribute, millions of elements) would cost
// that much before VTK could complain. Real .vti markup is a few kilobytes:
// stream the file up to <AppendedData> (VTK's parser stops there too) and
// count the bytes of tags and comments (a '>' inside a quoted attribute value
// does not end a tag); text between tags is inline array data and is bounded
// by the size check below instead.
void checkMarkupSize(std::istream& in, const std::string& name) {
  static const std::string kAppended = "<AppendedData";
  std::vector<char> buf(1 << 16);
  std::uintmax_t markup = 0;
  enum class In { Text, Tag, Comment } where = In::Text;
  char quote = 0;               // in a tag: the quote of the attribute value we are in, if any
  std::size_t matched = 0;      // characters of kAppended seen so far (in text)
  std::size_t tagChars = 0;     // characters of the current tag so far
  char last[4] = {0, 0, 0, 0};  // the last four characters, to see "<!--" and "-->"
  while (in) {
    in.read(buf.data(), std::streamsize(buf.size()));
    const std::size_t got = std::size_t(in.gcount());
    for (std::size_t i = 0; i < got; ++i) {
      const char c = buf[i];
      last[0] = last[1], last[1] = last[2], last[2] = last[3], last[3] = c;
      if (where == In::Text) {
        matched = c == kAppended[matched] ? matched + 1 : (c == '<' ? 1 : 0);
        if (matched == kAppended.size()) return;
        if (c == '<') where = In::Tag, tagChars = 0, quote = 0;
      } else if (where == In::Tag) {
        // Quotes in a comment mean nothing: "<!--" makes the rest a comment.
        if (++tagChars == 3 && last[0] == '<' && last[1] == '!' && last[2] == '-' && last[3] == '-') where = In::Comment;
        else if (c == '"' || c == '\'') quote = quote == 0 ? c : (quote == c ? 0 : quote);
        else if (c == '>' && quote == 0) where = In::Text;
      } else if (last[1] == '-' && last[2] == '-' && last[3] == '>') {
        where = In::Text;
      }
      if ((where != In::Text || c == '>') && ++markup > kMaxHeaderBytes)
        throw VolumeError(name + ": the VTK XML markup (elements, attributes and comments; not array data) passes " +
                          std::to_string(kMaxHeaderBytes) +
                          " bytes (1 MiB, the most MillSim reads of a header); is this a .vti file?");
    }
  }
}

}  // namespace

VoxelVolume medical::readVti(const fs::path& file, float airValue) {
  const std::string name = file.string();
  requireFile(file, "a .vti file");
  std::streamoff fileBytes = 0;
  bool compressed = false;
  {
    // VTK XML files start with "<?xml" or "<VTKFile" (after an optional byte-order mark and spaces).
    std::ifstream in(file, std::ios::binary);
    std::string head(4096, '\0');
    in.read(head.data(), std::streamsize(head.size()));
    head.resize(std::size_t(in.gcount()));
    if (head.rfind("\xEF\xBB\xBF", 0) == 0) head = head.substr(3);
    head = trim(head);
    // A compressor on the <VTKFile> element (zlib, LZ4 or LZMA) compresses every array.
    const std::size_t root = head.find("<VTKFile");
    if (root != std::string::npos) {
      const std::size_t rootEnd = head.find('>', root);
      compressed = head.substr(root, rootEnd == std::string::npos ? std::string::npos : rootEnd - root)
                       .find("compressor=") != std::string::npos;
    }
    if (head.rfind("<?xml", 0) != 0 && head.rfind("<VTKFile", 0) != 0)
      throw VolumeError(name + ": not an XML file (a .vti file starts with '<?xml' or '<VTKFile')");
    in.clear();
    in.seekg(0);
    checkMarkupSize(in, name);
    // VTK parses the XML only up to <AppendedData>, so a file cut inside appended raw data
    // would be read as garbage without an error. Every complete file ends with </VTKFile>.
    in.clear();
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    fileBytes = size;
    const std::streamoff tail = std::min<std::streamoff>(size, 256);
    std::string end(std::size_t(tail), '\0');
    in.seekg(size - tail);
    in.read(end.data(), tail);
    end = trim(end);
    if (end.size() < 10 || end.compare(end.size() - 10, 10, "</VTKFile>") != 0)
      throw VolumeError(name + ": truncated file: it does not end with </VTKFile>");
  }

  VtkMessages messages;  // outlives the reader, which holds its callback
  vtkNew<vtkXMLImageDataReader> reader;
  messages.watch(reader);
  reader->SetParserErrorObserver(messages.command);  // the XML parser reports on its own object
  reader->SetReaderErrorObserver(messages.command);
  reader->SetFileName(name.c_str());
  reader->UpdateInformation();
  if (!messages.text.empty()) throw VolumeError(name + ": cannot read as VTK XML image data: " + messages.text);

  vtkInformation* info = reader->GetOutputInformation(0);
  int ext[6] = {0, -1, 0, -1, 0, -1};
  double sp[3] = {0, 0, 0};
  if (!info || !info->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
    throw VolumeError(name + ": not VTK XML image data (no ImageData WholeExtent)");
  info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), ext);
  if (info->Has(vtkDataObject::SPACING())) info->Get(vtkDataObject::SPACING(), sp);
  const long long ext64[3] = {static_cast<long long>(ext[1]) - ext[0] + 1, static_cast<long long>(ext[3]) - ext[2] + 1,
                              static_cast<long long>(ext[5]) - ext[4] + 1};
  for (long long e : ext64)
    if (e > (1ll << 31) - 1) throw VolumeError(name + ": extent too large for a volume");
  const glm::ivec3 dims{int(ext64[0]), int(ext64[1]), int(ext64[2])};
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(sp[a]) || sp[a] <= 0.0)
      throw VolumeError(name + ": spacing along " + "xyz"[a] + " is " + fmt(sp[a]) +
                        " mm; spacing must be a positive finite number of millimetres");
  const glm::dvec3 spacing = glm::dvec3(sp[0], sp[1], sp[2]) / 1000.0;
  checkVolumeShape(name, dims, spacing);  // before VTK allocates the data
  if (reader->GetNumberOfPointArrays() == 0)
    throw VolumeError(name + ": no point data arrays (cell data is not supported: values must be on the voxels)");
  {
    // VTK allocates every point array (up to 8 bytes a value) before it reads
    // one. Each value takes at least a byte in the file (raw, base64 or ascii
    // "0 "), or 1/kMaxDeflateRatio of one compressed (zlib's bound; LZ4's is
    // lower, LZMA's higher only for near-constant data), so a small file that
    // declares a huge extent is refused here, before that allocation.
    const std::uintmax_t values = std::uintmax_t(dims.x) * std::uintmax_t(dims.y) * std::uintmax_t(dims.z) *
                                  std::uintmax_t(reader->GetNumberOfPointArrays());
    const std::uintmax_t have = std::uintmax_t(std::max<std::streamoff>(fileBytes, 0));
    if (compressed ? deflateCannotHold(have, values) : have < values)
      throw VolumeError(name + ": header/size mismatch: WholeExtent declares " + std::to_string(dims.x) + "x" +
                        std::to_string(dims.y) + "x" + std::to_string(dims.z) + " voxels in " +
                        std::to_string(reader->GetNumberOfPointArrays()) + " point data array(s), at least " +
                        (compressed ? std::to_string(values / kMaxDeflateRatio) + " bytes compressed"
                                    : std::to_string(values) + " bytes") +
                        "; the file has " + std::to_string(have));
  }

  reader->Update();
  if (!messages.text.empty()) throw VolumeError(name + ": " + messages.text);
  vtkImageData* image = reader->GetOutput();
  int d[3] = {0, 0, 0};
  if (image) image->GetDimensions(d);
  if (!image || d[0] != dims.x || d[1] != dims.y || d[2] != dims.z)
    throw VolumeError(name + ": VTK could not read the image data (got " + std::to_string(d[0]) + "x" +
                      std::to_string(d[1]) + "x" + std::to_string(d[2]) + ")");
  vtkPointData* pd = image->GetPointData();
  vtkDataArray* scalars = pd->GetScalars();
  if (!scalars) {
    if (pd->GetNumberOfArrays() == 1) scalars = pd->GetArray(0);
    if (!scalars)
      throw VolumeError(name + ": " + std::to_string(pd->GetNumberOfArrays()) +
                        " point data arrays and none is marked Scalars; cannot tell which one holds the densities");
  }
  if (scalars->GetNumberOfComponents() != 1)
    throw VolumeError(name + ": array '" + std::string(scalars->GetName() ? scalars->GetName() : "") + "' has " +
                      std::to_string(scalars->GetNumberOfComponents()) +
                      " components per voxel: multi-component data is not supported");
  const std::size_t n = std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z);
  if (std::size_t(scalars->GetNumberOfTuples()) != n)
    throw VolumeError(name + ": header/size mismatch: the extent promises " + std::to_string(n) + " values, array '" +
                      std::string(scalars->GetName() ? scalars->GetName() : "") + "' has " +
                      std::to_string(scalars->GetNumberOfTuples()));
  VolumeBuilder volume(dims, spacing, airValue, name);
  try {
    appendFloats(scalars, volume);
  } catch (const std::runtime_error& e) {
    throw VolumeError(name + ": " + e.what());
  }
  return volume.finish();
}

}  // namespace millsim
