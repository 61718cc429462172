#pragma once
// What the volume readers share: limits, so that a hostile file costs little
// before it is refused, and the small text helpers of their headers.
//
// Reading the text header of a volume file (NRRD, MetaImage) line by line
// with a cap on the whole header. std::getline would read a 1 GB line into
// memory before any check could see it, and a header that never ends (no
// blank line, no ElementDataFile) would be read to the end of the file; here
// either is a VolumeError naming the file and the limit once kMaxHeaderBytes
// have been read. Real headers are a few hundred bytes to a few kilobytes.
// Internal to millsim/volume (listed in cmake/private-headers.txt).
#include <cctype>
#include <cstdint>
#include <istream>
#include <sstream>
#include <string>
#include <vector>

#include "millsim/volume/VoxelVolume.h"

namespace millsim {

// Header keys and values compare case-blind (ASCII), as the formats' readers do.
inline std::string asciiLower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}
inline std::string trim(const std::string& s) {
  std::size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}
// The white-space separated words of a header value.
inline std::vector<std::string> words(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> w;
  for (std::string t; in >> t;) w.push_back(t);
  return w;
}
// A number as a stream prints it, for messages.
inline std::string fmt(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

inline constexpr std::uintmax_t kMaxHeaderBytes = std::uintmax_t(1) << 20;  // 1 MiB

// Deflate (zlib, gzip) expands at most about 1032:1, so compressed data that
// cannot hold what a header promises is refused before the voxels are
// allocated (a 1 KB file claiming 1024³ voxels would otherwise cost 4 GB first).
inline constexpr std::uintmax_t kMaxDeflateRatio = 1032;
// True when `compressedBytes` of deflate data cannot expand to `wantBytes`.
inline bool deflateCannotHold(std::uintmax_t compressedBytes, std::uintmax_t wantBytes) {
  return compressedBytes * kMaxDeflateRatio + 1024 < wantBytes;
}

class HeaderLines {
public:
  // `format` names the header in messages ("NRRD", "MetaImage"); `ending`
  // says what ends it ("a blank line", "an ElementDataFile line").
  HeaderLines(std::istream& in, std::string name, std::string format, std::string ending)
      : in_(in), name_(std::move(name)), format_(std::move(format)), ending_(std::move(ending)) {}

  // The next line without its "\n" or "\r\n"; false at the end of the file.
  // Throws VolumeError once the header passes kMaxHeaderBytes.
  bool next(std::string& line) {
    line.clear();
    std::streambuf* b = in_.rdbuf();
    bool any = false;
    for (;;) {
      const int c = b->sbumpc();
      if (c == std::char_traits<char>::eof()) break;
      any = true;
      if (++consumed_ > kMaxHeaderBytes) tooLong();
      if (c == '\n') break;
      line.push_back(static_cast<char>(c));
    }
    if (!any) return false;
    ++lineNumber_;
    lineStart_ = consumed_;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
  }

  std::uintmax_t consumed() const { return consumed_; }  // bytes read so far, newlines included
  int lineNumber() const { return lineNumber_; }         // lines returned so far

private:
  [[noreturn]] void tooLong() const {
    const std::string limit = std::to_string(kMaxHeaderBytes) + " bytes (1 MiB, the most MillSim reads of a header)";
    if (consumed_ - lineStart_ > kMaxHeaderBytes / 2)
      throw VolumeError(name_ + ": line " + std::to_string(lineNumber_ + 1) + " of the " + format_ +
                        " header is longer than " + limit + "; is this a " + format_ + " file?");
    throw VolumeError(name_ + ": the " + format_ + " header does not end within " + limit + "; " + ending_ +
                      " ends it; is this a " + format_ + " file?");
  }

  std::istream& in_;
  std::string name_, format_, ending_;
  std::uintmax_t consumed_ = 0, lineStart_ = 0;
  int lineNumber_ = 0;
};

}  // namespace millsim
