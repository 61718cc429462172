// checkVdbStructure: the .vdb layout it walks is OpenVDB's (io/Archive.cc,
// io/GridDescriptor.cc, MetaMap.cc, file versions 222-224, native little-endian):
//   header: int64 magic 0x56444220, uint32 file version, uint32 library major
//     and minor, char "has grid offsets", 36-byte UUID;
//   the file's metadata: int32 count, then per entry a string name, a string
//     type name and a uint32 value size with the value (a string is a uint32
//     length and its bytes);
//   int32 grid count, then per grid a descriptor: string name, string type,
//     string instance parent, int64 grid, block and end offsets; at the grid
//     offset, uint32 compression flags and the grid's metadata as above. With
//     offsets, the next descriptor starts at the end offset.
#include "millsim/volume/VdbStructureCheck.h"

#include <cstdint>
#include <fstream>

#include "millsim/volume/VolumeError.h"

namespace millsim {

namespace {

constexpr std::uint64_t kMagic = 0x56444220;
// The versions whose layout is walked here: 222 added per-grid compression
// flags; 224 is OpenVDB 10's. A later one may lay its header out otherwise,
// so it is left to OpenVDB (and the child process that reads it first).
constexpr std::uint32_t kFirstCheckedVersion = 222, kLastCheckedVersion = 224;
// Names and type names are short; a value (a string, a bounding box) small. A
// length above this is corrupt even where the file is long enough to hold it.
constexpr std::uint32_t kMaxString = 1u << 20;

class Reader {
public:
  Reader(std::ifstream& in, std::uint64_t size, const std::string& name) : in_(in), size_(size), name_(name) {}

  std::uint64_t at() const { return pos_; }
  std::uint64_t left() const { return size_ - pos_; }

  template <class T> T read(const char* what) {
    need(sizeof(T), what);
    T v{};
    in_.read(reinterpret_cast<char*>(&v), sizeof(T));
    if (!in_) fail(what, "cannot be read");
    pos_ += sizeof(T);
    return v;
  }
  void skip(std::uint64_t n, const char* what) {
    need(n, what);
    pos_ += n;
    in_.seekg(std::streamoff(pos_));
  }
  void string(const char* what) {
    const std::uint64_t start = pos_;
    const std::uint32_t n = read<std::uint32_t>(what);
    if (n > kMaxString)
      fail(what, "has the length " + std::to_string(n) + " at byte " + std::to_string(start) + " (at most " +
                     std::to_string(kMaxString) + " expected)");
    skip(n, what);
  }
  void seek(std::uint64_t p, const char* what) {
    if (p > size_)
      fail(what, "points to byte " + std::to_string(p) + ", past the end of the file (" + std::to_string(size_) +
                     " bytes)");
    pos_ = p;
    in_.seekg(std::streamoff(pos_));
  }
  // Entries need at least `minBytes` each: a count the rest of the file cannot hold is corrupt.
  void count(std::int64_t n, std::uint64_t minBytes, const char* what) {
    if (n < 0 || std::uint64_t(n) > left() / minBytes)
      fail(what, "is " + std::to_string(n) + " at byte " + std::to_string(pos_ - 4) + ", where the " +
                     std::to_string(left()) + " bytes left hold at most " + std::to_string(left() / minBytes));
  }
  [[noreturn]] void fail(const char* what, const std::string& how) const {
    throw VolumeError(name_ + ": corrupt OpenVDB file: the " + what + " " + how);
  }

private:
  void need(std::uint64_t n, const char* what) const {
    if (n > left())
      fail(what, "at byte " + std::to_string(pos_) + " needs " + std::to_string(n) + " bytes, and " +
                     std::to_string(left()) + " are left");
  }

  std::ifstream& in_;
  std::uint64_t size_;
  std::uint64_t pos_ = 0;
  const std::string& name_;
};

void metaMap(Reader& r, const char* countName) {
  const std::int32_t n = r.read<std::int32_t>(countName);
  r.count(n, 12, countName);  // a name, a type name and a value size: 12 bytes at least
  for (std::int32_t i = 0; i < n; ++i) {
    r.string("metadata name");
    r.string("metadata type name");
    const std::uint32_t size = r.read<std::uint32_t>("metadata value size");
    r.skip(size, "metadata value");
  }
}

}  // namespace

void checkVdbStructure(const std::filesystem::path& file, const std::string& name) {
  std::ifstream in(file, std::ios::binary);
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  if (!in || ec) return;  // the reader says why it cannot open it
  Reader r(in, size, name);
  if (size < 8 || r.read<std::uint64_t>("magic number") != kMagic) return;  // not a .vdb: OpenVDB says so
  const std::uint32_t version = r.read<std::uint32_t>("file version");
  r.read<std::uint32_t>("library major version");
  r.read<std::uint32_t>("library minor version");
  if (version < kFirstCheckedVersion || version > kLastCheckedVersion) return;
  const bool offsets = r.read<char>("grid offsets flag") != 0;
  r.skip(36, "file UUID");
  metaMap(r, "file metadata count");
  const std::int32_t grids = r.read<std::int32_t>("grid count");
  r.count(grids, 36, "grid count");  // three strings and three offsets
  for (std::int32_t g = 0; g < grids; ++g) {
    r.string("grid name");
    r.string("grid type name");
    r.string("grid instance parent name");
    const auto gridPos = r.read<std::int64_t>("grid offset");
    const auto blockPos = r.read<std::int64_t>("grid block offset");
    const auto endPos = r.read<std::int64_t>("grid end offset");
    if (offsets) {
      if (gridPos < std::int64_t(r.at()) || blockPos < gridPos || endPos < blockPos)
        r.fail("grid offsets", "are " + std::to_string(gridPos) + ", " + std::to_string(blockPos) + " and " +
                                   std::to_string(endPos) + " after byte " + std::to_string(r.at()) +
                                   " (increasing, from there, expected)");
      r.seek(std::uint64_t(endPos), "grid end offset");
      r.seek(std::uint64_t(gridPos), "grid offset");
    }
    r.read<std::uint32_t>("grid compression flags");
    metaMap(r, "grid metadata count");
    if (!offsets) return;  // the grid's transform and tree follow: not walked here
    r.seek(std::uint64_t(endPos), "grid end offset");
  }
}

}  // namespace millsim
