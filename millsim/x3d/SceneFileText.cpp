#include "millsim/x3d/SceneFileText.h"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>

namespace millsim {

namespace fs = std::filesystem;

std::optional<std::string> unsupportedEncoding(const fs::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  const char* what = nullptr;
  if (ext == ".x3dv" || ext == ".x3dvz") what = "the X3D ClassicVRML encoding";
  else if (ext == ".x3dj" || ext == ".json") what = "the X3D JSON encoding";
  else if (ext == ".wrl") what = "VRML97";
  else if (ext == ".x3db") what = "the X3D binary encoding";
  if (!what) return std::nullopt;
  return "'" + file.string() + "' is " + what + ", which is not supported: MillSim reads the XML encoding "
         "(.x3d, .x3d.gz, .x3dz); convert the file, e.g. with view3dscene's tovrmlx3d --encoding=xml";
}

std::optional<LocalSceneFile> localSceneFile(const std::string& url, const fs::path& dir, std::string& tried) {
  if (url.find("://") != std::string::npos) {
    tried += "\n  " + url + ": network URLs are not allowed";
    return std::nullopt;
  }
  fs::path p = fs::path(url).is_absolute() ? fs::path(url) : dir / url;
  if (auto unsupported = unsupportedEncoding(p)) {
    tried += "\n  " + *unsupported;
    return std::nullopt;
  }
  std::error_code ec;
  if (!fs::is_regular_file(p, ec)) {
    tried += "\n  " + p.string() + ": no such file";
    return std::nullopt;
  }
  fs::path canonical = fs::weakly_canonical(p, ec);
  return LocalSceneFile{std::move(p), std::move(canonical)};
}

namespace {

std::optional<std::string> inflateGzip(const std::string& in, std::uintmax_t maxBytes, std::string& out,
                                       const fs::path& file) {
  z_stream z{};
  if (inflateInit2(&z, 16 + MAX_WBITS) != Z_OK) return std::string("cannot start zlib");
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data()));
  z.avail_in = static_cast<uInt>(in.size());
  out.clear();
  char buf[1 << 16];
  int rc = Z_OK;
  while (rc != Z_STREAM_END) {
    z.next_out = reinterpret_cast<Bytef*>(buf);
    z.avail_out = sizeof buf;
    rc = inflate(&z, Z_NO_FLUSH);
    if (rc != Z_OK && rc != Z_STREAM_END) {
      inflateEnd(&z);
      return "'" + file.string() + "' starts like gzip data but does not inflate (" + (z.msg ? z.msg : "corrupt or cut short") + ")";
    }
    out.append(buf, sizeof buf - z.avail_out);
    // An inflation bomb stops at the same cap as a plain file.
    if (out.size() > maxBytes) {
      inflateEnd(&z);
      return "'" + file.string() + "' inflates to more than " + std::to_string(maxBytes) +
             " bytes; X3D text over that is refused";
    }
    if (rc == Z_OK && z.avail_in == 0 && z.avail_out != 0) {
      inflateEnd(&z);
      return "'" + file.string() + "' is cut short: its gzip data ends early";
    }
  }
  inflateEnd(&z);
  return std::nullopt;
}

}  // namespace

std::optional<std::string> readSceneText(const fs::path& file, std::uintmax_t maxBytes, std::string& out) {
  std::error_code ec;
  const auto size = fs::file_size(file, ec);
  if (ec) return "cannot read '" + file.string() + "': " + ec.message();
  if (size > maxBytes)
    return "'" + file.string() + "' is " + std::to_string(size) + " bytes; X3D files over " + std::to_string(maxBytes) +
           " bytes are refused";
  std::ifstream in(file, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  if (!in) return "cannot read '" + file.string() + "'";
  std::string raw = ss.str();
  if (raw.size() >= 2 && static_cast<unsigned char>(raw[0]) == 0x1f && static_cast<unsigned char>(raw[1]) == 0x8b)
    return inflateGzip(raw, maxBytes, out, file);
  out = std::move(raw);
  return std::nullopt;
}

}  // namespace millsim
