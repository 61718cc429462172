// NRRD files (.nrrd with attached data, .nhdr with a detached data file): readNrrd and writeNrrd.
//
// Not through VTK: VTK 9.1's vtkNrrdReader (checked on Debian 12) reads
// attached ascii data from the start of the header (garbage values), does not
// byte-swap big-endian gzip data, flips y for "space: left-anterior-superior",
// turns any volume whose first size is 9 or less into a multi-component image
// (an 8x64x64 volume becomes 8 components of 64x64x1), and reports truncated
// raw data only as a warning. The format is a short text header, so we parse
// it here, check every size before allocating, and read raw, gzip (zlib) and
// ascii data ourselves.
//
// Index order is the file's order (first axis fastest); orientation ("space
// directions") contributes only the spacing (the length of each direction
// vector), in millimetres.
#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <zlib.h>

#include "millsim/volume/InflateAhead.h"
#include "millsim/volume/ReaderLimits.h"
#include "millsim/volume/VolumeBuilder.h"
#include "millsim/volume/VolumeIO.h"

namespace fs = std::filesystem;

namespace millsim {

namespace {

enum class Scalar { Int8, UInt8, Int16, UInt16, Int32, UInt32, Int64, UInt64, Float, Double };

std::size_t scalarBytes(Scalar t) {
  switch (t) {
    case Scalar::Int8:
    case Scalar::UInt8: return 1;
    case Scalar::Int16:
    case Scalar::UInt16: return 2;
    case Scalar::Int32:
    case Scalar::UInt32:
    case Scalar::Float: return 4;
    default: return 8;
  }
}

std::optional<Scalar> nrrdType(const std::string& s) {
  static const std::vector<std::pair<std::vector<std::string>, Scalar>> names = {
      {{"signed char", "int8", "int8_t"}, Scalar::Int8},
      {{"uchar", "unsigned char", "uint8", "uint8_t"}, Scalar::UInt8},
      {{"short", "short int", "signed short", "signed short int", "int16", "int16_t"}, Scalar::Int16},
      {{"ushort", "unsigned short", "unsigned short int", "uint16", "uint16_t"}, Scalar::UInt16},
      {{"int", "signed int", "int32", "int32_t"}, Scalar::Int32},
      {{"uint", "unsigned int", "uint32", "uint32_t"}, Scalar::UInt32},
      {{"longlong", "long long", "long long int", "signed long long", "signed long long int", "int64", "int64_t"},
       Scalar::Int64},
      {{"ulonglong", "unsigned long long", "unsigned long long int", "uint64", "uint64_t"}, Scalar::UInt64},
      {{"float"}, Scalar::Float},
      {{"double"}, Scalar::Double},
  };
  for (const auto& [list, t] : names)
    if (std::find(list.begin(), list.end(), s) != list.end()) return t;
  return std::nullopt;
}

// Parses a whole token as a number; NaN and inf are accepted here and refused by the callers.
bool parseDouble(const std::string& s, double& out) {
  if (s.empty()) return false;
  char* end = nullptr;
  errno = 0;
  out = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size();
}

bool parseInteger(const std::string& s, long long& out) {
  if (s.empty()) return false;
  char* end = nullptr;
  errno = 0;
  out = std::strtoll(s.c_str(), &end, 10);
  return errno == 0 && end == s.c_str() + s.size();
}

// Converts little- or big-endian values to float as bytes arrive, in any
// chunking, into the volume being built (a slab at a time: no dense copy).
class Converter {
public:
  Converter(Scalar type, bool swap, VolumeBuilder& out)
      : type_(type), swap_(swap), bytes_(scalarBytes(type)), out_(out) {}

  // Returns the number of bytes consumed (stops when every voxel has its value).
  std::size_t feed(const unsigned char* p, std::size_t len) {
    std::size_t used = 0;
    while (used < len && out_.room() > 0) {
      if (carryLen_ > 0 || len - used < bytes_) {
        const std::size_t take = std::min(bytes_ - carryLen_, len - used);
        std::memcpy(carry_.data() + carryLen_, p + used, take);
        carryLen_ += take;
        used += take;
        if (carryLen_ == bytes_) {
          *out_.next() = one(carry_.data());
          out_.advance(1);
          carryLen_ = 0;
        }
        continue;
      }
      const std::size_t whole = std::min((len - used) / bytes_, out_.room());
      float* to = out_.next();
      for (std::size_t i = 0; i < whole; ++i) to[i] = one(p + used + i * bytes_);
      out_.advance(whole);
      used += whole * bytes_;
    }
    return used;
  }

private:
  template <typename T>
  float as(const unsigned char* p) const {
    unsigned char b[sizeof(T)];
    std::memcpy(b, p, sizeof(T));
    if (swap_) std::reverse(b, b + sizeof(T));
    T v;
    std::memcpy(&v, b, sizeof(T));
    return static_cast<float>(v);
  }
  float one(const unsigned char* p) const {
    switch (type_) {
      case Scalar::Int8: return as<std::int8_t>(p);
      case Scalar::UInt8: return as<std::uint8_t>(p);
      case Scalar::Int16: return as<std::int16_t>(p);
      case Scalar::UInt16: return as<std::uint16_t>(p);
      case Scalar::Int32: return as<std::int32_t>(p);
      case Scalar::UInt32: return as<std::uint32_t>(p);
      case Scalar::Int64: return as<std::int64_t>(p);
      case Scalar::UInt64: return as<std::uint64_t>(p);
      case Scalar::Float: return as<float>(p);
      case Scalar::Double: return as<double>(p);
    }
    return 0.f;
  }

  Scalar type_;
  bool swap_;
  std::size_t bytes_;
  VolumeBuilder& out_;
  std::array<unsigned char, 8> carry_{};
  std::size_t carryLen_ = 0;
};

struct NrrdHeader {
  int dimension = 0;
  std::vector<long long> sizes;
  std::vector<double> spacings;    // from "spacings"
  std::vector<double> directions;  // lengths of "space directions" (NaN for "none")
  std::string typeName;
  std::string encoding = "raw";
  std::string endian;
  std::string dataFile;  // empty: data follows the header
  long long byteSkip = 0;
  long long lineSkip = 0;
  std::vector<std::string> kinds;
  std::uintmax_t headerBytes = 0;  // where attached data starts
};

NrrdHeader parseHeader(const fs::path& file) {
  const std::string name = file.string();
  std::ifstream in(file, std::ios::binary);
  if (!in) throw VolumeError(name + ": cannot open the file");
  NrrdHeader h;
  std::string line;
  // Capped: a header that never ends, or one endless line, stops at kMaxHeaderBytes.
  HeaderLines lines(in, name, "NRRD", "a blank line");
  auto nextLine = [&]() -> bool { return lines.next(line); };
  if (!nextLine() || line.rfind("NRRD000", 0) != 0)
    throw VolumeError(name + ": not a NRRD file (the first line must be NRRD0001 to NRRD0005)");

  bool ended = false;
  while (nextLine()) {
    if (line.empty()) {
      ended = true;
      break;
    }
    if (line[0] == '#') continue;
    const std::size_t colon = line.find(": ");
    if (colon == std::string::npos) {
      if (line.find(":=") != std::string::npos) continue;  // key/value pair, not a field
      throw VolumeError(name + ": malformed NRRD header line '" + line + "' (expected 'field: value')");
    }
    const std::string field = asciiLower(trim(line.substr(0, colon)));
    const std::string value = trim(line.substr(colon + 2));
    const auto bad = [&](const std::string& what) {
      return VolumeError(name + ": bad NRRD field '" + field + ": " + value + "': " + what);
    };
    if (field == "dimension") {
      long long d;
      if (!parseInteger(value, d) || d < 1 || d > 16) throw bad("expected a small positive integer");
      h.dimension = int(d);
    } else if (field == "sizes") {
      for (const auto& w : words(value)) {
        long long s;
        if (!parseInteger(w, s) || s < 1) throw bad("sizes must be positive integers");
        h.sizes.push_back(s);
      }
    } else if (field == "spacings") {
      for (const auto& w : words(value)) {
        double s;
        if (!parseDouble(w, s)) throw bad("'" + w + "' is not a number");
        h.spacings.push_back(s);
      }
    } else if (field == "space directions") {
      for (const auto& w : words(value)) {
        if (w == "none") {
          h.directions.push_back(std::nan(""));
          continue;
        }
        if (w.size() < 2 || w.front() != '(' || w.back() != ')') throw bad("expected vectors like (0.5,0,0) or none");
        std::istringstream v(w.substr(1, w.size() - 2));
        double sum = 0.0;
        int n = 0;
        for (std::string c; std::getline(v, c, ',');) {
          double x;
          if (!parseDouble(trim(c), x)) throw bad("'" + c + "' is not a number");
          sum += x * x;
          ++n;
        }
        if (n == 0) throw bad("empty direction vector");
        h.directions.push_back(std::sqrt(sum));
      }
    } else if (field == "type") {
      h.typeName = value;
    } else if (field == "encoding") {
      h.encoding = asciiLower(value);
    } else if (field == "endian") {
      h.endian = asciiLower(value);
    } else if (field == "data file" || field == "datafile") {
      h.dataFile = value;
    } else if (field == "byte skip" || field == "byteskip") {
      if (!parseInteger(value, h.byteSkip) || h.byteSkip < -1) throw bad("expected -1 or a byte count");
    } else if (field == "line skip" || field == "lineskip") {
      if (!parseInteger(value, h.lineSkip) || h.lineSkip < 0) throw bad("expected a line count");
    } else if (field == "kinds") {
      h.kinds = words(value);
    }
    // Other fields (space, space origin, units, labels, centers, ...) do not change the voxels.
  }
  h.headerBytes = lines.consumed();
  if (!ended && h.dataFile.empty())
    throw VolumeError(name + ": the NRRD header has no 'data file' field and no blank line after it, so there is no data");
  return h;
}

std::uintmax_t fileSize(const fs::path& f, const std::string& name) {
  std::error_code ec;
  const auto s = fs::file_size(f, ec);
  if (ec) throw VolumeError(name + ": cannot read the size of data file " + f.string() + ": " + ec.message());
  return s;
}

std::string promised(std::uintmax_t bytes, glm::ivec3 d, const std::string& typeName) {
  return std::to_string(bytes) + " bytes (" + std::to_string(d.x) + "x" + std::to_string(d.y) + "x" +
         std::to_string(d.z) + " " + typeName + ")";
}

}  // namespace

VoxelVolume readNrrd(const fs::path& file, float airValue) {
  const std::string name = file.string();
  requireFile(file, "a NRRD file");
  const NrrdHeader h = parseHeader(file);

  // --- Shape: one component, three spatial axes.
  if (h.dimension == 0) throw VolumeError(name + ": the NRRD header has no 'dimension' field");
  for (std::size_t a = 0; a < h.kinds.size(); ++a) {
    const std::string k = asciiLower(h.kinds[a]);
    if (k != "domain" && k != "space" && k != "???" && k != "none")
      throw VolumeError(name + ": axis " + std::to_string(a) + " has kind '" + h.kinds[a] +
                        "': multi-component data is not supported (one value per voxel, three spatial axes)");
  }
  if (h.dimension == 4)
    throw VolumeError(name + ": 4-dimensional NRRD data (several components per voxel or time steps) is not "
                             "supported: one value per voxel, three spatial axes");
  if (h.dimension != 3)
    throw VolumeError(name + ": dimension " + std::to_string(h.dimension) + ": only 3-D volumes are supported");
  if (h.sizes.size() != 3)
    throw VolumeError(name + ": header/size mismatch: 'sizes' lists " + std::to_string(h.sizes.size()) +
                      " numbers but 'dimension' is 3");
  for (long long s : h.sizes)
    if (s > INT_MAX)
      throw VolumeError(name + ": size " + std::to_string(s) + " is too large for a volume (limit " +
                        std::to_string(kMaxVoxels) + " voxels)");
  const glm::ivec3 dims(int(h.sizes[0]), int(h.sizes[1]), int(h.sizes[2]));

  // --- Spacing (millimetres).
  std::vector<double> sp = !h.directions.empty() ? h.directions : h.spacings;
  const char* spField = !h.directions.empty() ? "space directions" : "spacings";
  if (sp.empty())
    throw VolumeError(name + ": no 'spacings' or 'space directions' field: the voxel spacing is unknown");
  if (sp.size() != 3)
    throw VolumeError(name + ": header/size mismatch: '" + spField + "' has " + std::to_string(sp.size()) +
                      " entries but 'dimension' is 3");
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(sp[a]) || sp[a] <= 0.0)
      throw VolumeError(name + ": spacing along " + "xyz"[a] + " is " + fmt(sp[a]) +
                        " mm; spacing must be a positive finite number of millimetres");
  const glm::dvec3 spacing = glm::dvec3(sp[0], sp[1], sp[2]) / 1000.0;
  checkVolumeShape(name, dims, spacing);  // before anything is allocated

  // --- Type, encoding, data location.
  if (h.typeName.empty()) throw VolumeError(name + ": the NRRD header has no 'type' field");
  const auto type = nrrdType(h.typeName);
  if (!type)
    throw VolumeError(name + ": unsupported NRRD type '" + h.typeName +
                      "' (supported: int8, uint8, int16, uint16, int32, uint32, int64, uint64, float, double)");
  std::string enc = h.encoding;
  if (enc == "gz") enc = "gzip";
  if (enc == "txt" || enc == "text") enc = "ascii";
  if (enc != "raw" && enc != "gzip" && enc != "ascii")
    throw VolumeError(name + ": unsupported NRRD encoding '" + h.encoding + "' (supported: raw, gzip, ascii)");
  const std::size_t bytes = scalarBytes(*type);
  if (enc != "ascii" && bytes > 1 && h.endian != "little" && h.endian != "big")
    throw VolumeError(name + ": " + (h.endian.empty() ? std::string("no 'endian' field") : "endian '" + h.endian + "'") +
                      ": " + h.typeName + " data needs 'endian: little' or 'endian: big'");
  const bool swap = (h.endian == "big") != (std::endian::native == std::endian::big) && bytes > 1;
  if (h.lineSkip != 0) throw VolumeError(name + ": 'line skip' is not supported");
  if (h.byteSkip == -1 && enc != "raw") throw VolumeError(name + ": 'byte skip: -1' is only valid with raw encoding");

  fs::path dataPath = file;
  std::uintmax_t offset = h.headerBytes;
  if (!h.dataFile.empty()) {
    const auto w = words(h.dataFile);
    if (w.size() != 1 || w[0] == "LIST" || h.dataFile.find('%') != std::string::npos)
      throw VolumeError(name + ": data split over several files ('data file: " + h.dataFile + "') is not supported");
    dataPath = fs::path(h.dataFile).is_absolute() ? fs::path(h.dataFile) : file.parent_path() / h.dataFile;
    std::error_code ec;
    if (!fs::is_regular_file(dataPath, ec))
      throw VolumeError(name + ": data file " + dataPath.string() + " does not exist");
    offset = 0;
  }

  const std::size_t n = std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z);
  const std::uintmax_t want = std::uintmax_t(n) * bytes;
  const std::uintmax_t size = fileSize(dataPath, name);
  const std::string where = h.dataFile.empty() ? "the file" : "data file " + dataPath.string();
  if (h.byteSkip == -1) {
    offset = size >= want ? size - want : 0;
  } else {
    offset += std::uintmax_t(h.byteSkip);
  }
  const std::uintmax_t available = size > offset ? size - offset : 0;

  if (enc == "raw") {
    if (available < want)
      throw VolumeError(name + ": truncated data: the header promises " + promised(want, dims, h.typeName) + ", " +
                        where + " has " + std::to_string(available));
    if (available > want)
      throw VolumeError(name + ": header/size mismatch: the header promises " + promised(want, dims, h.typeName) +
                        ", " + where + " has " + std::to_string(available));
  }

  // Compressed data that cannot expand to what the header promises is refused
  // before the voxels are allocated (ReaderLimits.h).
  if (enc == "gzip" && deflateCannotHold(available, want))
    throw VolumeError(name + ": truncated data: the header promises " + promised(want, dims, h.typeName) + ", but " +
                      where + " holds only " + std::to_string(available) +
                      " compressed bytes, which gzip cannot expand that far");
  // ASCII needs at least two characters (a digit and a separator) per value.
  if (enc == "ascii" && available < 2 * std::uintmax_t(n) - 1)
    throw VolumeError(name + ": truncated data: the header promises " + std::to_string(n) + " values, but " + where +
                      " has only " + std::to_string(available) + " characters");

  std::ifstream data(dataPath, std::ios::binary);
  if (!data) throw VolumeError(name + ": cannot open " + where);
  data.seekg(std::streamoff(offset));
  VolumeBuilder volume(dims, spacing, airValue, name);
  Converter conv(*type, swap, volume);
  std::vector<unsigned char> chunk(1 << 18);

  if (enc == "raw") {
    std::uintmax_t left = want;
    while (left > 0) {
      const std::size_t k = std::size_t(std::min<std::uintmax_t>(left, chunk.size()));
      data.read(reinterpret_cast<char*>(chunk.data()), std::streamsize(k));
      if (std::size_t(data.gcount()) != k) throw VolumeError(name + ": read error in " + where);
      conv.feed(chunk.data(), k);
      left -= k;
    }
  } else if (enc == "gzip") {
    // Inflated on another thread, up to a slab of the builder ahead of the
    // conversion, so that zlib goes on while a slab goes into the grid
    // (InflateAhead.h). A stream that holds more than the header promises
    // stops at the first chunk over.
    const std::size_t slabBytes = volume.slabValues() * scalarBytes(*type);
    std::optional<InflateAhead> ahead;
    try {
      ahead.emplace(data, 15 + 32, std::min<std::size_t>(slabBytes, std::size_t(128) << 20));
    } catch (const std::runtime_error&) {
      throw VolumeError(name + ": cannot start zlib");
    }
    std::uintmax_t produced = 0;
    std::string error;
    for (InflateAhead::Chunk c = ahead->next(); c.size > 0; c = ahead->next()) {
      if (produced + c.size > want) {
        error = "header/size mismatch: the gzip data holds more than the " + promised(want, dims, h.typeName) +
                " the header promises";
        break;
      }
      conv.feed(c.data, c.size);
      produced += c.size;
    }
    if (error.empty() && ahead->end() == InflateAhead::End::Corrupt)
      error = "corrupt gzip data (" + ahead->message() + ")";
    else if (error.empty() && ahead->end() == InflateAhead::End::Truncated)
      error = "truncated data: the gzip stream ends early; the header promises " + promised(want, dims, h.typeName) +
              ", it holds " + std::to_string(produced);
    if (!error.empty()) throw VolumeError(name + ": " + error);
    if (produced < want)
      throw VolumeError(name + ": truncated data: the header promises " + promised(want, dims, h.typeName) +
                        ", the gzip data holds " + std::to_string(produced));
  } else {  // ascii
    std::string text((std::istreambuf_iterator<char>(data)), std::istreambuf_iterator<char>());
    std::size_t count = 0;
    const char* p = text.c_str();
    const char* end = p + text.size();
    while (true) {
      while (p < end && (std::isspace(static_cast<unsigned char>(*p)) || *p == ',')) ++p;
      if (p >= end) break;
      char* q = nullptr;
      const double v = std::strtod(p, &q);
      if (q == p || (q < end && !std::isspace(static_cast<unsigned char>(*q)) && *q != ',')) {
        const char* e = p;
        while (e < end && !std::isspace(static_cast<unsigned char>(*e)) && e - p < 20) ++e;
        throw VolumeError(name + ": bad number '" + std::string(p, e) + "' in the ascii data");
      }
      if (count < n) {
        *volume.next() = static_cast<float>(v);
        volume.advance(1);
      }
      ++count;
      p = q;
    }
    if (count < n)
      throw VolumeError(name + ": truncated data: the header promises " + std::to_string(n) + " values, " + where +
                        " has " + std::to_string(count));
    if (count > n)
      throw VolumeError(name + ": header/size mismatch: the header promises " + std::to_string(n) + " values, " +
                        where + " has " + std::to_string(count));
  }
  return volume.finish();
}

void writeNrrd(const VoxelVolume& volume, const fs::path& file, bool gzip) {
  const std::string name = file.string();
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  if (!out) throw VolumeError(name + ": cannot open for writing");
  const glm::ivec3 d = volume.dims();
  const glm::dvec3 mm = volume.voxelSize() * 1000.0;
  std::ostringstream hdr;
  hdr.precision(17);
  hdr << "NRRD0004\n"
      << "# MillSim volume: densities (Hounsfield-like units), spacings in millimetres\n"
      << "type: float\n"
      << "dimension: 3\n"
      << "sizes: " << d.x << " " << d.y << " " << d.z << "\n"
      << "spacings: " << mm.x << " " << mm.y << " " << mm.z << "\n"
      << "units: \"mm\" \"mm\" \"mm\"\n"
      << "kinds: domain domain domain\n"
      << "endian: little\n"
      << "encoding: " << (gzip ? "gzip" : "raw") << "\n\n";
  out << hdr.str();

  z_stream zs{};
  if (gzip && deflateInit2(&zs, Z_DEFAULT_COMPRESSION, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK)
    throw VolumeError(name + ": cannot start zlib");
  std::vector<unsigned char> slice(std::size_t(d.x) * std::size_t(d.y) * 4);
  std::vector<unsigned char> zout(1 << 18);
  auto deflateSome = [&](unsigned char* in, std::size_t len, int flush) {
    zs.next_in = in;
    zs.avail_in = uInt(len);
    do {
      zs.next_out = zout.data();
      zs.avail_out = uInt(zout.size());
      deflate(&zs, flush);
      out.write(reinterpret_cast<const char*>(zout.data()), std::streamsize(zout.size() - zs.avail_out));
    } while (zs.avail_out == 0);
  };
  const auto& grid = volume.grid();
  auto acc = grid.getConstAccessor();
  const float air = volume.airValue();
  for (int k = 0; k < d.z; ++k) {
    std::size_t o = 0;
    for (int j = 0; j < d.y; ++j)
      for (int i = 0; i < d.x; ++i) {
        const openvdb::Coord c(i, j, k);
        const float v = acc.isValueOn(c) ? acc.getValue(c) : air;
        std::uint32_t u;
        std::memcpy(&u, &v, 4);
        slice[o++] = static_cast<unsigned char>(u);
        slice[o++] = static_cast<unsigned char>(u >> 8);
        slice[o++] = static_cast<unsigned char>(u >> 16);
        slice[o++] = static_cast<unsigned char>(u >> 24);
      }
    if (gzip)
      deflateSome(slice.data(), slice.size(), Z_NO_FLUSH);
    else
      out.write(reinterpret_cast<const char*>(slice.data()), std::streamsize(slice.size()));
  }
  if (gzip) {
    deflateSome(nullptr, 0, Z_FINISH);
    deflateEnd(&zs);
  }
  out.close();
  if (!out) throw VolumeError(name + ": write failed (disk full?)");
}

}  // namespace millsim
