// loadVolume: picks the reader for a VolumeObject url.
#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <set>
#include <string>

#include "millsim/volume/MeshVolume.h"
#include "millsim/volume/ReaderLimits.h"
#include "millsim/volume/ToothPhantom.h"
#include "millsim/volume/VolumeIO.h"

namespace fs = std::filesystem;

namespace millsim {

namespace {

const char* const kSupported =
    ".vdb, .nrrd, .nhdr, .mha, .mhd, .vti, .dcm, a folder of DICOM slices, a folder, pattern (slice_%04d.tif) or "
    "multi-page .tif of TIFF, PNG or BMP slices, phantom:tooth, or a surface mesh (.stl, .obj, .ply) with the VolumeObject's "
    "voxelSize";

// "scheme:" at the start of a url (two or more letters, so that "C:" is not one).
std::string urlScheme(const std::string& url) {
  std::size_t i = 0;
  while (i < url.size() && (std::isalnum(static_cast<unsigned char>(url[i])) || url[i] == '+' || url[i] == '-' ||
                            url[i] == '.'))
    ++i;
  if (i >= 2 && i < url.size() && url[i] == ':' && std::isalpha(static_cast<unsigned char>(url[0])))
    return asciiLower(url.substr(0, i));
  return "";
}

// What a path that is neither a regular file nor a folder is, for the message.
std::string kindOf(const fs::file_status& st) {
  switch (st.type()) {
    case fs::file_type::fifo: return "a FIFO (named pipe)";
    case fs::file_type::socket: return "a socket";
    case fs::file_type::block: return "a block device";
    case fs::file_type::character: return "a character device";
    default: return "not a regular file";
  }
}

// DICOM Part 10 files carry "DICM" after a 128-byte preamble; slices often have no extension.
bool hasDicomMagic(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  char b[132];
  return in.read(b, 132) && b[128] == 'D' && b[129] == 'I' && b[130] == 'C' && b[131] == 'M';
}

}  // namespace

bool isSliceImageFile(const fs::path& path) {
  const std::string ext = asciiLower(path.extension().string());
  return ext == ".tif" || ext == ".tiff" || ext == ".png" || ext == ".bmp";
}

bool isSliceStackPattern(const std::string& path) {
  // Only a slice file name's own %d counts: a folder may have a '%' in its name.
  const fs::path p(path);
  const std::string file = p.filename().string();
  if (!isSliceImageFile(p)) return false;
  const std::size_t pct = file.find('%');
  if (pct == std::string::npos) return false;
  std::size_t i = pct + 1;
  while (i < file.size() && std::isdigit(static_cast<unsigned char>(file[i]))) ++i;
  return i < file.size() && file[i] == 'd' && file.find('%', pct + 1) == std::string::npos;
}

namespace {

bool isTiffFile(const fs::path& p) {
  const std::string ext = asciiLower(p.extension().string());
  return ext == ".tif" || ext == ".tiff";
}

// A folder of TIFF, PNG or BMP slices (a micro-CT stack) rather than DICOM ones:
// such files and no DICOM file (a stray preview .tif in a DICOM series stays DICOM).
bool holdsImageSlices(const fs::path& folder) {
  std::error_code ec;
  bool images = false;
  int unnamed = 0;
  for (const auto& e : fs::directory_iterator(folder, ec)) {
    if (!e.is_regular_file(ec)) continue;
    const std::string ext = asciiLower(e.path().extension().string());
    if (ext == ".dcm" || ext == ".dicom") return false;
    if (ext.empty() && ++unnamed <= 16 && hasDicomMagic(e.path())) return false;
    images |= isSliceImageFile(e.path());
  }
  return images;
}

// A local url (a path, file:///path or file:path) as a path, relative ones against baseDir.
fs::path localVolumePath(const std::string& url, const fs::path& baseDir) {
  const std::string scheme = urlScheme(url);
  std::string pathText = url;
  if (scheme == "file") {
    // file:///abs/path or file:relative/path
    pathText = url.substr(5);
    if (pathText.rfind("//", 0) == 0) {
      pathText = pathText.substr(2);
      if (!pathText.empty() && pathText[0] != '/') {
        const std::size_t slash = pathText.find('/');
        const std::string host = pathText.substr(0, slash);
        if (host != "localhost")
          throw VolumeError(url + ": file urls on other hosts are not supported (only local files)");
        pathText = slash == std::string::npos ? "" : pathText.substr(slash);
      }
    }
  } else if (!scheme.empty()) {
    throw VolumeError(url + ": '" + scheme + ":' urls are not supported; volumes are read from local files only (" +
                      kSupported + ")");
  }
  fs::path path(pathText);
  if (path.is_relative() && !baseDir.empty()) path = baseDir / path;
  return path.lexically_normal();
}

// What `check` says of a voxelised mesh: format, parts, unit, size, voxels.
std::string meshAccount(const MeshVolume& m, const MeshVoxelOptions& mesh) {
  std::string account = m.format + ", " + std::to_string(m.parts.size()) + (m.parts.size() == 1 ? " part" : " parts");
  for (std::size_t i = 0; i < m.parts.size(); ++i)
    account += std::string(i ? ", '" : " ('") + m.parts[i] + "' " + std::to_string(m.triangles[i]) + " triangles" +
               (i + 1 == m.parts.size() ? ")" : "");
  const glm::dvec3 mm = m.size * 1e3;
  return account + ", " + fmt(mesh.unit) + " m per unit of the file (the format carries none, meshUnit says it): " +
         fmt(mm.x) + " × " + fmt(mm.y) + " × " + fmt(mm.z) + " mm, voxelised at " + fmt(mesh.voxelSize * 1e3) +
         " mm into " + std::to_string(m.density.dims().x) + " × " + std::to_string(m.density.dims().y) + " × " +
         std::to_string(m.density.dims().z) + " voxels";
}

void requireVoxelSize(const std::string& name, const MeshVoxelOptions* mesh) {
  if (!mesh || !(mesh->voxelSize > 0.0))
    throw VolumeError(name + ": a surface mesh has no voxels; the VolumeObject's voxelSize says how fine to voxelise "
                             "it (e.g. voxelSize='0.00005 0.00005 0.00005' for 50 µm)");
}

}  // namespace

LoadedVolume loadMeshParts(const std::vector<std::string>& urls, const fs::path& baseDir, const MeshVoxelOptions& mesh) {
  std::string names;
  for (const std::string& u : urls) names += (names.empty() ? "" : " + ") + u;
  requireVoxelSize(names, &mesh);
  SurfaceMesh all;
  std::map<std::string, std::string> partFile;  // part name → the file that has it
  std::set<std::string> formats;
  for (const std::string& u : urls) {
    const fs::path path = localVolumePath(u, baseDir);
    SurfaceMesh m = readSurfaceMesh(path);
    formats.insert(m.format);
    // A file of one part is the part of its name (enamel.stl: 'enamel'); a file of several keeps its parts' names.
    if (m.parts.size() == 1) m.parts[0].name = path.stem().string();
    for (MeshPart& p : m.parts) {
      if (const auto [it, added] = partFile.emplace(p.name, path.string()); !added)
        throw VolumeError(path.string() + ": part '" + p.name + "' is a part of " + it->second +
                          " too; each part of a VolumeObject needs its own name");
      if (all.parts.size() == kMaxMeshParts)
        throw VolumeError(names + ": more than " + std::to_string(kMaxMeshParts) + " parts; MillSim voxelises at most that many");
      all.parts.push_back(std::move(p));
    }
  }
  for (const std::string& f : formats) all.format += (all.format.empty() ? "" : " and ") + f;
  MeshVolume v = voxeliseMesh(all, names, mesh);
  const std::string account = meshAccount(v, mesh);
  return LoadedVolume{std::move(v.density), v.format, names, std::move(v.labels), std::move(v.parts), account};
}

LoadedVolume loadVolume(const std::string& url, const fs::path& baseDir, float airValue, const MeshVoxelOptions* mesh,
                        glm::dvec3 voxelSize) {
  if (url.empty()) throw VolumeError("(empty url): no volume file given (expected " + std::string(kSupported) + ")");
  if (urlScheme(url) == "phantom") return LoadedVolume{makeToothPhantom(parsePhantomUrl(url)), "phantom", url};
  const fs::path path = localVolumePath(url, baseDir);
  const std::string name = path.string();
  if (isSliceStackPattern(name)) return LoadedVolume{readSliceStack(path, airValue, voxelSize), "slices", name};
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st)) throw VolumeError(name + ": no such file or folder");
  if (fs::is_directory(st) && holdsImageSlices(path))
    return LoadedVolume{readSliceStack(path, airValue, voxelSize), "slices", name};
  if (fs::is_directory(st)) return LoadedVolume{readDicom(path, airValue), "dicom", name};
  // Reading a FIFO would wait forever and a device such as /dev/zero never ends.
  if (!fs::is_regular_file(st))
    throw VolumeError(name + ": is " + kindOf(st) + "; volumes are read from regular files or folders");

  const std::string ext = asciiLower(path.extension().string());
  if (ext == ".vdb") return LoadedVolume{readVdb(path, airValue), "vdb", name};
  if (ext == ".nrrd" || ext == ".nhdr") return LoadedVolume{readNrrd(path, airValue), "nrrd", name};
  if (ext == ".mha" || ext == ".mhd") return LoadedVolume{readMetaImage(path, airValue), "metaimage", name};
  if (ext == ".vti") return LoadedVolume{readVti(path, airValue), "vti", name};
  if (isTiffFile(path)) return LoadedVolume{readSliceStack(path, airValue, voxelSize), "slices", name};
  if (isMeshFile(path)) {
    requireVoxelSize(name, mesh);
    MeshVolume m = loadMeshVolume(path, *mesh);
    const std::string account = meshAccount(m, *mesh);
    return LoadedVolume{std::move(m.density), m.format, name, std::move(m.labels), std::move(m.parts), account};
  }
  if (ext == ".dcm" || ext == ".dicom" || (ext.empty() && hasDicomMagic(path)))
    return LoadedVolume{readDicom(path, airValue), "dicom", name};
  throw VolumeError(name + ": unknown volume file extension '" + path.extension().string() + "' (supported: " +
                    kSupported + ")");
}

void requireFile(const std::filesystem::path& file, const std::string& what) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw VolumeError(file.string() + ": no such file");
  if (std::filesystem::is_directory(file, ec)) throw VolumeError(file.string() + ": is a folder, not " + what);
  const auto st = std::filesystem::status(file, ec);
  if (!std::filesystem::is_regular_file(st))
    throw VolumeError(file.string() + ": is " + kindOf(st) + ", not " + what + " (a regular file)");
}

}  // namespace millsim
