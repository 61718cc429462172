// DICOM CT slices (a folder of slices or one file): readDicom.
//
// Library choice: GDCM (Debian libgdcm-dev), not VTK's vtkDICOMImageReader.
// GDCM reads any tag (Modality, SeriesInstanceUID, rescale slope/intercept,
// ImagePositionPatient/ImageOrientationPatient, BitsStored) and decodes the
// compressed transfer syntaxes (JPEG, JPEG-LS, JPEG 2000, RLE, deflate).
// vtkDICOMImageReader exposes neither Modality nor SeriesInstanceUID, decodes
// only uncompressed data, and returns the rows bottom-up (checked against pydicom).
// Neither library is safe on truncated files (checked on Debian 12): GDCM
// 3.0.21 is built with assertions and aborts the process on a file cut inside a
// sequence item (gdcmItem.h:207), and both return a "successful" image when
// the pixel data is cut short. So every file is first walked element by
// element here (checkStructure) and refused if any element runs past the end.
//
// Index mapping: i runs along a row (DICOM column index, fastest), j along
// the column (DICOM row index: j = 0 is the top row of the image as stored,
// and j grows downwards, along the second ImageOrientationPatient vector), and
// k along the slice normal (row direction x column direction) in increasing
// ImagePositionPatient projection. Values are stored value x slope + intercept
// (Hounsfield units for CT).
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include <gdcmImage.h>
#include <gdcmImageReader.h>
#include <gdcmPixelFormat.h>
#include <gdcmReader.h>
#include <gdcmStringFilter.h>
#include <gdcmTag.h>
#include <gdcmTrace.h>

#include <zlib.h>

#include "millsim/volume/ReaderLimits.h"
#include "millsim/volume/MedicalModule.h"
#include "millsim/volume/VolumeBuilder.h"
#include "millsim/volume/VolumeIO.h"

namespace fs = std::filesystem;

namespace millsim {

namespace {

// DICOM pads its strings with spaces or NULs.
std::string trimPadded(const std::string& s) {
  std::size_t b = 0, e = s.size();
  while (b < e && (std::isspace(static_cast<unsigned char>(s[b])) || s[b] == '\0')) ++b;
  while (e > b && (std::isspace(static_cast<unsigned char>(s[e - 1])) || s[e - 1] == '\0')) --e;
  return s.substr(b, e - b);
}

std::string hex4(unsigned v) {
  char b[8];
  std::snprintf(b, sizeof b, "%04x", v & 0xffffu);
  return b;
}

// ---------------------------------------------------------------------------
// Structure check: every element and item must lie inside the file. It also
// picks up the few top-level facts that let us refuse non-CT files and
// non-images before GDCM parses them (Debian's GDCM asserts on some odd
// files, e.g. pydicom's DICOMDIR-nooffset).

// One slice file is read whole (twice: here and by GDCM); a 4096x4096 slice
// of 32-bit pixels is 64 MiB, more than any CT slice (512x512 or 1024x1024).
constexpr std::uint64_t kMaxDicomSliceBytes = std::uint64_t(64) << 20;

struct DicomFacts {
  bool walked = false;  // the whole data set was walked
  std::string sopClass, modality;
  bool pixelData = false;
  bool encapsulated = false;          // Pixel Data of undefined length: compressed fragments
  std::uint64_t pixelDataBytes = 0;   // its value length, or the sum of its fragments
};

class StructureCheck {
public:
  StructureCheck(std::string name, std::vector<unsigned char> bytes) : name_(std::move(name)), b_(std::move(bytes)) {}

  DicomFacts run() {
    std::size_t pos = 0;
    if (b_.size() >= 132 && std::memcmp(&b_[128], "DICM", 4) == 0) pos = 132;
    std::string ts;
    bool meta = false;
    if (pos + 4 <= b_.size() && u16(pos, false) == 0x0002) {
      // File meta information: always explicit VR little endian.
      meta = true;
      while (pos + 4 <= b_.size() && u16(pos, false) == 0x0002) {
        const Element e = header(pos, true, false);
        if (e.undefined) fail("file meta element (0002," + hex4(e.element) + ") has an undefined length");
        need(e.value, e.length, e);
        if (e.element == 0x0002) facts_.sopClass = text(e);
        if (e.element == 0x0010) ts = text(e);
        pos = e.value + e.length;
      }
    }
    if (ts == "1.2.840.10008.1.2.1.99") {
      // Deflated explicit VR little endian: walk the inflated data set the same way.
      b_ = inflateDataSet(pos);
      pos = 0;
      ts = "1.2.840.10008.1.2.1";
      inflated_ = true;
    }
    // The transfer syntax decides; without one (or when the data contradicts it, which GDCM
    // tolerates) look at the first element: big endian puts the group's high byte first, and
    // explicit VR has two upper-case letters after the tag.
    bool big = ts == "1.2.840.10008.1.2.2";
    bool explicitVr = ts != "1.2.840.10008.1.2";
    if (pos + 6 <= b_.size()) {
      if (!meta || ts.empty()) big = u16(pos, true) < u16(pos, false);
      const bool looksExplicit = std::isupper(b_[pos + 4]) && std::isupper(b_[pos + 5]);
      if (!meta || ts.empty() || (explicitVr && !looksExplicit)) explicitVr = looksExplicit;
    }
    dataSet(pos, explicitVr, big, false, 0);
    facts_.walked = true;
    return facts_;
  }

private:
  struct Element {
    unsigned group = 0, element = 0;
    char vr[3] = {0, 0, 0};
    std::size_t start = 0, value = 0;
    std::uint32_t length = 0;
    bool undefined = false;
  };

  [[noreturn]] void fail(const std::string& what) const {
    throw VolumeError(name_ + ": " + what + (inflated_ ? " (byte offsets in the inflated data set)" : ""));
  }

  // The raw deflate stream after the file meta information, inflated with the
  // same bounds as any compressed volume data: at most kMaxDeflateRatio times
  // its size and at most kMaxDicomSliceBytes.
  std::vector<unsigned char> inflateDataSet(std::size_t pos) const {
    const std::uint64_t compressed = b_.size() - pos;
    const std::uint64_t cap = std::min<std::uint64_t>(compressed * kMaxDeflateRatio + 1024, kMaxDicomSliceBytes);
    std::vector<unsigned char> out;
    z_stream z{};
    if (inflateInit2(&z, -MAX_WBITS) != Z_OK) fail("cannot start inflating the deflated data set");
    z.next_in = const_cast<unsigned char*>(b_.data() + pos);
    z.avail_in = uInt(compressed);
    int rc = Z_OK;
    while (rc == Z_OK) {
      if (out.size() >= cap) {
        inflateEnd(&z);
        fail("the deflated data set inflates beyond " + std::to_string(cap) + " bytes (from " +
             std::to_string(compressed) + " compressed; at most " + std::to_string(kMaxDeflateRatio) +
             " times that and at most " + std::to_string(kMaxDicomSliceBytes) + " bytes per slice)");
      }
      const std::size_t have = out.size();
      const std::size_t want = std::size_t(std::min<std::uint64_t>(cap, have + (std::uint64_t(1) << 20)));
      // Grow by doubling, but never reserve past the cap.
      if (want > out.capacity()) out.reserve(std::size_t(std::min<std::uint64_t>(cap, std::max(want, 2 * out.capacity()))));
      out.resize(want);
      z.next_out = out.data() + have;
      z.avail_out = uInt(out.size() - have);
      rc = inflate(&z, Z_NO_FLUSH);
      out.resize(out.size() - z.avail_out);
      if (rc == Z_BUF_ERROR && z.avail_in == 0) break;  // the stream ends without its final block
      if (rc == Z_BUF_ERROR) rc = Z_OK;                 // needed more room: go round
    }
    inflateEnd(&z);
    if (rc != Z_STREAM_END)
      fail("the deflated data set is corrupt or truncated (zlib: " + std::string(z.msg ? z.msg : "incomplete stream") +
           ")");
    return out;
  }
  std::string text(const Element& e) const {
    return trimPadded(std::string(reinterpret_cast<const char*>(&b_[e.value]), e.length));
  }

  unsigned u16(std::size_t p, bool big) const {
    return big ? (unsigned(b_[p]) << 8) | b_[p + 1] : unsigned(b_[p]) | (unsigned(b_[p + 1]) << 8);
  }
  std::uint32_t u32(std::size_t p, bool big) const {
    return big ? (std::uint32_t(u16(p, true)) << 16) | u16(p + 2, true) : u16(p, false) | (std::uint32_t(u16(p + 2, false)) << 16);
  }
  void need(std::size_t at, std::uint64_t n, const Element& e) const {
    if (at + n > b_.size())
      fail("truncated DICOM file: element (" + hex4(e.group) + "," + hex4(e.element) + ") at byte " +
           std::to_string(e.start) + " needs " + std::to_string(n) + " bytes, the file has " +
           std::to_string(at > b_.size() ? 0 : b_.size() - at) + " left");
  }

  Element header(std::size_t pos, bool explicitVr, bool big) const {
    Element e;
    e.start = pos;
    if (pos + 8 > b_.size())
      fail("truncated DICOM file: it ends inside an element header at byte " + std::to_string(pos));
    e.group = u16(pos, big);
    e.element = u16(pos + 2, big);
    if (e.group == 0xfffe || !explicitVr) {
      e.length = u32(pos + 4, big);
      e.value = pos + 8;
    } else {
      e.vr[0] = char(b_[pos + 4]);
      e.vr[1] = char(b_[pos + 5]);
      if (!std::isupper(b_[pos + 4]) || !std::isupper(b_[pos + 5]))
        fail("malformed DICOM file: element (" + hex4(e.group) + "," + hex4(e.element) + ") at byte " +
             std::to_string(pos) + " has no valid value representation");
      static const char* longVr[] = {"OB", "OD", "OF", "OL", "OV", "OW", "SQ", "SV", "UC", "UN", "UR", "UT", "UV"};
      bool isLong = false;
      for (const char* v : longVr) isLong = isLong || (e.vr[0] == v[0] && e.vr[1] == v[1]);
      if (isLong) {
        if (pos + 12 > b_.size())
          fail("truncated DICOM file: it ends inside an element header at byte " + std::to_string(pos));
        e.length = u32(pos + 8, big);
        e.value = pos + 12;
      } else {
        e.length = u16(pos + 6, big);
        e.value = pos + 8;
      }
    }
    e.undefined = e.length == 0xffffffffu;
    return e;
  }

  // Walks elements from pos; inside an item of undefined length, stops after its delimiter.
  std::size_t dataSet(std::size_t pos, bool explicitVr, bool big, bool inItem, int depth) {
    if (depth > 32) fail("malformed DICOM file: sequences nested more than 32 deep");
    while (pos < b_.size()) {
      const Element e = header(pos, explicitVr, big);
      if (e.group == 0xfffe && e.element == 0xe00d) {
        if (!inItem) fail("malformed DICOM file: item delimiter outside an item at byte " + std::to_string(pos));
        return e.value;
      }
      const bool pixels = depth == 0 && e.group == 0x7fe0 && e.element == 0x0010;
      if (pixels) facts_.pixelData = true;
      if (!e.undefined) {
        if (pixels) facts_.pixelDataBytes = e.length;
        need(e.value, e.length, e);
        if (depth == 0 && e.group == 0x0008 && e.element == 0x0060) facts_.modality = text(e);
        pos = e.value + e.length;
        continue;
      }
      // Undefined length: a sequence, or encapsulated pixel data; both are lists of items.
      // Inside UN of undefined length the content is implicit VR little endian (CP-246).
      const bool un = e.vr[0] == 'U' && e.vr[1] == 'N';
      const std::size_t start = e.value;
      pos = items(e.value, un ? false : explicitVr, un ? false : big, depth, e);
      if (pixels) {
        facts_.encapsulated = true;
        facts_.pixelDataBytes = pos - start;
      }
    }
    if (inItem) fail("truncated DICOM file: it ends inside a sequence item");
    return pos;
  }

  std::size_t items(std::size_t pos, bool explicitVr, bool big, int depth, const Element& owner) {
    while (true) {
      if (pos + 8 > b_.size())
        fail("truncated DICOM file: it ends inside element (" + hex4(owner.group) + "," + hex4(owner.element) + ")");
      Element it = header(pos, false, big);
      if (it.group == 0xfffe && it.element == 0xe0dd) return it.value;  // sequence delimiter
      if (it.group != 0xfffe || it.element != 0xe000)
        fail("malformed DICOM file: expected an item in element (" + hex4(owner.group) + "," + hex4(owner.element) +
             ") at byte " + std::to_string(pos));
      if (it.undefined) {
        pos = dataSet(it.value, explicitVr, big, true, depth + 1);
      } else {
        it.group = owner.group;
        it.element = owner.element;
        need(it.value, it.length, it);
        pos = it.value + it.length;
      }
    }
  }

  std::string name_;
  std::vector<unsigned char> b_;
  bool inflated_ = false;
  DicomFacts facts_;
};

void refuseModality(const std::string& name, const std::string& modality) {
  if (modality.empty())
    throw VolumeError(name + ": no Modality (0008,0060): only CT images (Hounsfield units) are supported");
  if (modality != "CT")
    throw VolumeError(name + ": modality is " + modality + ", not CT: only CT images (Hounsfield units) are supported");
}

// Throws unless the file is structurally complete and, as far as can be told without GDCM, a CT image.
DicomFacts checkStructure(const fs::path& file) {
  const std::string name = file.string();
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(file, ec);
  if (!ec && size > kMaxDicomSliceBytes)
    throw VolumeError(name + ": " + std::to_string(size) + " bytes is more than one DICOM slice may have (" +
                      std::to_string(kMaxDicomSliceBytes) + " bytes, a 4096x4096 slice of 32 bits)");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw VolumeError(name + ": cannot open the file");
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const DicomFacts facts = StructureCheck(name, std::move(bytes)).run();
  if (facts.sopClass == "1.2.840.10008.1.3.10")
    throw VolumeError(name + ": is a DICOMDIR (an index of other files), not an image; give the folder of slices");
  if (!facts.walked) return facts;
  refuseModality(name, facts.modality);
  if (!facts.pixelData) throw VolumeError(name + ": no Pixel Data (7fe0,0010): not an image");
  return facts;
}

// ---------------------------------------------------------------------------
// Slice headers.

struct Slice {
  fs::path file;
  std::string modality, series;
  unsigned rows = 0, cols = 0;
  double rowSpacing = 0, colSpacing = 0;  // PixelSpacing: between rows, between columns (mm)
  bool hasPosition = false, hasOrientation = false;
  std::array<double, 3> position{};
  std::array<double, 6> orientation{1, 0, 0, 0, 1, 0};
  double thickness = std::nan(""), spacingBetween = std::nan("");
  double slope = 1, intercept = 0;
  double along = 0;  // position projected on the slice normal
};

std::vector<double> numbers(const std::string& s) {
  std::vector<double> v;
  std::istringstream in(s);
  for (std::string t; std::getline(in, t, '\\');) {
    t = trimPadded(t);
    if (t.empty()) continue;
    char* end = nullptr;
    const double x = std::strtod(t.c_str(), &end);
    if (*end != '\0') return {};
    v.push_back(x);
  }
  return v;
}

Slice readSliceHeader(const fs::path& file) {
  const std::string name = file.string();
  const DicomFacts facts = checkStructure(file);
  gdcm::Reader reader;
  reader.SetFileName(name.c_str());
  if (!reader.ReadUpToTag(gdcm::Tag(0x7fe0, 0x0010)))
    throw VolumeError(name + ": cannot read the DICOM header (corrupt or not DICOM)");
  gdcm::StringFilter sf;
  sf.SetFile(reader.GetFile());
  const auto str = [&](std::uint16_t g, std::uint16_t e) { return trimPadded(sf.ToString(gdcm::Tag(g, e))); };

  Slice s;
  s.file = file;
  s.modality = str(0x0008, 0x0060);
  refuseModality(name, s.modality);
  s.series = str(0x0020, 0x000e);

  const std::string spp = str(0x0028, 0x0002);
  if (!spp.empty() && spp != "1")
    throw VolumeError(name + ": " + spp + " samples per pixel: multi-component (colour) images are not supported");
  const std::string frames = str(0x0028, 0x0008);
  if (!frames.empty() && std::atoi(frames.c_str()) > 1)
    throw VolumeError(name + ": multi-frame image (" + frames + " frames): only one slice per file is supported");
  s.rows = unsigned(std::atoi(str(0x0028, 0x0010).c_str()));
  s.cols = unsigned(std::atoi(str(0x0028, 0x0011).c_str()));
  if (s.rows == 0 || s.cols == 0) throw VolumeError(name + ": no Rows/Columns: not an image");
  const unsigned bits = unsigned(std::atoi(str(0x0028, 0x0100).c_str()));
  if (facts.walked && bits > 0) {
    // The declared image size against the Pixel Data the file holds, before
    // anything that size is allocated (GDCM's buffer, the volume). Native
    // data holds every byte; compressed fragments are allowed a generous
    // ratio (kMaxDeflateRatio plus 1 MiB: JPEG-LS and JPEG 2000 compress a
    // uniform slice further than deflate, but a slice is at most megabytes).
    const std::uint64_t declared = (std::uint64_t(s.rows) * s.cols * bits + 7) / 8;
    const std::string shape = std::to_string(s.cols) + "x" + std::to_string(s.rows) + " pixels of " +
                              std::to_string(bits) + " bits (" + std::to_string(declared) + " bytes)";
    if (!facts.encapsulated && facts.pixelDataBytes < declared)
      throw VolumeError(name + ": header/size mismatch: Rows/Columns/BitsAllocated declare " + shape +
                        ", Pixel Data (7fe0,0010) holds " + std::to_string(facts.pixelDataBytes) + " bytes");
    if (facts.encapsulated && declared > facts.pixelDataBytes * kMaxDeflateRatio + (std::uint64_t(1) << 20))
      throw VolumeError(name + ": header/size mismatch: Rows/Columns/BitsAllocated declare " + shape +
                        ", but the compressed Pixel Data (7fe0,0010) holds only " +
                        std::to_string(facts.pixelDataBytes) + " bytes, which cannot expand that far");
  }

  const auto ps = numbers(str(0x0028, 0x0030));
  if (ps.empty()) throw VolumeError(name + ": no PixelSpacing (0028,0030): the voxel spacing is unknown");
  if (ps.size() != 2 || !std::isfinite(ps[0]) || !std::isfinite(ps[1]) || ps[0] <= 0 || ps[1] <= 0)
    throw VolumeError(name + ": PixelSpacing '" + str(0x0028, 0x0030) +
                      "': spacing must be two positive finite numbers of millimetres");
  s.rowSpacing = ps[0];
  s.colSpacing = ps[1];

  const auto ipp = numbers(str(0x0020, 0x0032));
  if (ipp.size() == 3 && std::isfinite(ipp[0]) && std::isfinite(ipp[1]) && std::isfinite(ipp[2])) {
    s.hasPosition = true;
    std::copy(ipp.begin(), ipp.end(), s.position.begin());
  }
  const auto iop = numbers(str(0x0020, 0x0037));
  if (iop.size() == 6) {
    s.hasOrientation = true;
    std::copy(iop.begin(), iop.end(), s.orientation.begin());
  }
  const auto th = numbers(str(0x0018, 0x0050));
  if (th.size() == 1) s.thickness = th[0];
  const auto sb = numbers(str(0x0018, 0x0088));
  if (sb.size() == 1) s.spacingBetween = sb[0];
  const auto slope = numbers(str(0x0028, 0x1053));
  const auto intercept = numbers(str(0x0028, 0x1052));
  if (slope.size() == 1) s.slope = slope[0];
  if (intercept.size() == 1) s.intercept = intercept[0];
  if (!std::isfinite(s.slope) || !std::isfinite(s.intercept) || s.slope == 0.0)
    throw VolumeError(name + ": bad RescaleSlope/RescaleIntercept (" + fmt(s.slope) + ", " + fmt(s.intercept) + ")");
  return s;
}

std::array<double, 3> sliceNormal(const Slice& s) {
  const auto& o = s.orientation;
  std::array<double, 3> n{o[1] * o[5] - o[2] * o[4], o[2] * o[3] - o[0] * o[5], o[0] * o[4] - o[1] * o[3]};
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(len > 0.5)) throw VolumeError(s.file.string() + ": ImageOrientationPatient does not give two independent directions");
  for (double& x : n) x /= len;
  return n;
}

// ---------------------------------------------------------------------------
// Pixels.

template <typename T>
void convertSlice(const char* buffer, std::size_t count, const gdcm::PixelFormat& pf, double slope, double intercept,
                  float* out) {
  const unsigned allocated = pf.GetBitsAllocated(), stored = pf.GetBitsStored(), high = pf.GetHighBit();
  const bool mask = std::is_integral_v<T> && stored > 0 && stored < allocated && allocated <= 32;
  const unsigned shift = high + 1 >= stored ? high + 1 - stored : 0;
  for (std::size_t i = 0; i < count; ++i) {
    T raw;
    std::memcpy(&raw, buffer + i * sizeof(T), sizeof(T));
    double v;
    if constexpr (std::is_integral_v<T>) {
      if (mask) {
        // Only BitsStored bits (ending at HighBit) are the value; the rest may hold overlays.
        std::int64_t u = (static_cast<std::int64_t>(static_cast<std::make_unsigned_t<T>>(raw)) >> shift) &
                         ((std::int64_t(1) << stored) - 1);
        if (pf.GetPixelRepresentation() == 1 && (u & (std::int64_t(1) << (stored - 1)))) u -= std::int64_t(1) << stored;
        v = double(u);
      } else {
        v = double(raw);
      }
    } else {
      v = double(raw);
    }
    out[i] = static_cast<float>(v * slope + intercept);
  }
}

void readSlicePixels(const Slice& s, float* out) {
  const std::string name = s.file.string();
  gdcm::ImageReader reader;
  reader.SetFileName(name.c_str());
  if (!reader.Read()) throw VolumeError(name + ": cannot read the DICOM image");
  const gdcm::Image& image = reader.GetImage();
  if (image.GetColumns() != s.cols || image.GetRows() != s.rows)
    throw VolumeError(name + ": the image is " + std::to_string(image.GetColumns()) + "x" +
                      std::to_string(image.GetRows()) + " but the header says " + std::to_string(s.cols) + "x" +
                      std::to_string(s.rows));
  const gdcm::PixelFormat& pf = image.GetPixelFormat();
  if (pf.GetSamplesPerPixel() != 1)
    throw VolumeError(name + ": " + std::to_string(pf.GetSamplesPerPixel()) +
                      " samples per pixel: multi-component images are not supported");
  const std::size_t count = std::size_t(s.rows) * std::size_t(s.cols);
  const std::size_t bytes = count * pf.GetPixelSize();
  if (image.GetBufferLength() != bytes)
    throw VolumeError(name + ": pixel data length " + std::to_string(image.GetBufferLength()) + " does not match " +
                      std::to_string(s.cols) + "x" + std::to_string(s.rows) + " pixels of " +
                      std::to_string(pf.GetPixelSize()) + " bytes");
  std::vector<char> buffer(bytes);
  if (!image.GetBuffer(buffer.data()))
    throw VolumeError(name + ": cannot decode the pixel data (transfer syntax " +
                      std::string(image.GetTransferSyntax().GetString() ? image.GetTransferSyntax().GetString() : "?") +
                      ")");
  switch (pf.GetScalarType()) {
    case gdcm::PixelFormat::UINT8: convertSlice<std::uint8_t>(buffer.data(), count, pf, s.slope, s.intercept, out); break;
    case gdcm::PixelFormat::INT8: convertSlice<std::int8_t>(buffer.data(), count, pf, s.slope, s.intercept, out); break;
    case gdcm::PixelFormat::UINT16: convertSlice<std::uint16_t>(buffer.data(), count, pf, s.slope, s.intercept, out); break;
    case gdcm::PixelFormat::INT16: convertSlice<std::int16_t>(buffer.data(), count, pf, s.slope, s.intercept, out); break;
    case gdcm::PixelFormat::UINT32: convertSlice<std::uint32_t>(buffer.data(), count, pf, s.slope, s.intercept, out); break;
    case gdcm::PixelFormat::INT32: convertSlice<std::int32_t>(buffer.data(), count, pf, s.slope, s.intercept, out); break;
    case gdcm::PixelFormat::FLOAT32: convertSlice<float>(buffer.data(), count, pf, s.slope, s.intercept, out); break;
    case gdcm::PixelFormat::FLOAT64: convertSlice<double>(buffer.data(), count, pf, s.slope, s.intercept, out); break;
    default:
      throw VolumeError(name + ": unsupported pixel format (" + std::to_string(pf.GetBitsAllocated()) +
                        " bits allocated, pixel representation " + std::to_string(pf.GetPixelRepresentation()) + ")");
  }
}

bool isDicomCandidate(const fs::path& file) {
  const std::string fn = file.filename().string();
  if (fn.empty() || fn[0] == '.' || fn == "DICOMDIR") return false;
  gdcm::Reader r;
  r.SetFileName(file.string().c_str());
  return r.CanRead();
}

}  // namespace

VoxelVolume medical::readDicom(const fs::path& fileOrFolder, float airValue) {
  const std::string name = fileOrFolder.string();
  // GDCM prints warnings and errors on stderr by default; the exceptions carry the reasons.
  gdcm::Trace::SetDebug(false);
  gdcm::Trace::SetWarning(false);
  gdcm::Trace::SetError(false);

  std::error_code ec;
  const fs::file_status st = fs::status(fileOrFolder, ec);
  if (!fs::exists(st)) throw VolumeError(name + ": no such file or folder");

  std::vector<fs::path> files;
  if (fs::is_directory(st)) {
    std::vector<fs::path> all;
    for (const auto& entry : fs::directory_iterator(fileOrFolder, ec))
      if (entry.is_regular_file(ec)) all.push_back(entry.path());
    if (ec) throw VolumeError(name + ": cannot list the folder: " + ec.message());
    std::sort(all.begin(), all.end());
    for (const auto& f : all)
      if (isDicomCandidate(f)) files.push_back(f);
    if (files.empty())
      throw VolumeError(name + ": no DICOM files in " + name +
                        (all.empty() ? std::string(" (the folder is empty)")
                                     : " (" + std::to_string(all.size()) + " other files)"));
  } else {
    gdcm::Reader r;
    r.SetFileName(name.c_str());
    if (!r.CanRead()) throw VolumeError(name + ": not a DICOM file");
    files.push_back(fileOrFolder);
  }

  std::vector<Slice> slices;
  slices.reserve(files.size());
  for (const auto& f : files) slices.push_back(readSliceHeader(f));

  // One series, one geometry.
  const Slice& first = slices.front();
  for (const Slice& s : slices) {
    if (s.series != first.series)
      throw VolumeError(name + ": slices of more than one series (" + first.file.filename().string() + " is in " +
                        first.series + ", " + s.file.filename().string() + " in " + s.series + ")");
    if (s.rows != first.rows || s.cols != first.cols)
      throw VolumeError(name + ": slice " + s.file.filename().string() + " is " + std::to_string(s.cols) + "x" +
                        std::to_string(s.rows) + ", slice " + first.file.filename().string() + " is " +
                        std::to_string(first.cols) + "x" + std::to_string(first.rows));
    if (std::abs(s.rowSpacing - first.rowSpacing) > 1e-4 * first.rowSpacing ||
        std::abs(s.colSpacing - first.colSpacing) > 1e-4 * first.colSpacing)
      throw VolumeError(name + ": slices " + first.file.filename().string() + " and " + s.file.filename().string() +
                        " have different PixelSpacing");
    for (int a = 0; a < 6; ++a)
      if (std::abs(s.orientation[a] - first.orientation[a]) > 1e-4)
        throw VolumeError(name + ": slices " + first.file.filename().string() + " and " + s.file.filename().string() +
                          " have different ImageOrientationPatient");
  }

  double sliceSpacing = 0;
  if (slices.size() == 1) {
    const Slice& s = first;
    sliceSpacing = std::isfinite(s.thickness) && s.thickness > 0 ? s.thickness : s.spacingBetween;
    if (!std::isfinite(sliceSpacing) || sliceSpacing <= 0)
      throw VolumeError(name + ": one slice and no positive SliceThickness (0018,0050): the slice spacing is unknown");
  } else {
    for (const Slice& s : slices) {
      if (!s.hasPosition)
        throw VolumeError(s.file.string() + ": no ImagePositionPatient (0020,0032): cannot order the slices");
      if (!s.hasOrientation)
        throw VolumeError(s.file.string() + ": no ImageOrientationPatient (0020,0037): cannot order the slices");
    }
    const auto n = sliceNormal(first);
    for (Slice& s : slices) s.along = s.position[0] * n[0] + s.position[1] * n[1] + s.position[2] * n[2];
    std::stable_sort(slices.begin(), slices.end(), [](const Slice& a, const Slice& b) { return a.along < b.along; });
    const double mean = (slices.back().along - slices.front().along) / double(slices.size() - 1);
    for (std::size_t k = 1; k < slices.size(); ++k) {
      const double gap = slices[k].along - slices[k - 1].along;
      if (gap < 1e-3)
        throw VolumeError(name + ": slices " + slices[k - 1].file.filename().string() + " and " +
                          slices[k].file.filename().string() + " are at the same position (" +
                          fmt(slices[k].along) + " mm along the slice normal)");
      if (std::abs(gap - mean) > 0.01 * mean + 1e-3)
        throw VolumeError(name + ": slice spacing is not uniform: " + fmt(gap) + " mm between " +
                          slices[k - 1].file.filename().string() + " and " + slices[k].file.filename().string() +
                          ", " + fmt(mean) + " mm on average (missing slices?)");
    }
    sliceSpacing = mean;
  }

  const glm::ivec3 dims(int(first.cols), int(first.rows), int(slices.size()));
  const glm::dvec3 spacing = glm::dvec3(first.colSpacing, first.rowSpacing, sliceSpacing) / 1000.0;
  const std::size_t perSlice = std::size_t(first.rows) * std::size_t(first.cols);
  // A slice at a time into the volume being built (which checks the shape
  // before it allocates anything): no dense float copy of the series.
  VolumeBuilder volume(dims, spacing, airValue, name);
  std::vector<float> slice(perSlice);
  for (const Slice& s : slices) {
    readSlicePixels(s, slice.data());
    volume.append(slice.data(), perSlice);
  }
  return volume.finish();
}

}  // namespace millsim
