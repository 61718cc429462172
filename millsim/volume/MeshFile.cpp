// MeshFile (MeshFile.h): STL, OBJ and PLY readers, the open-edge count.
#include "millsim/volume/MeshFile.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <numeric>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "millsim/volume/ReaderLimits.h"
#include "millsim/volume/VolumeError.h"
#include "millsim/volume/VolumeIO.h"

namespace millsim {

namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxMeshLineBytes = 1 << 20;

// Text read a line at a time, each capped, counting lines for messages.
class MeshLines {
public:
  // `linesBefore`: lines already read (a PLY's header), so that numbers are the file's.
  MeshLines(std::istream& in, std::string name, std::size_t linesBefore = 0)
      : in_(in), name_(std::move(name)), number_(linesBefore) {}
  bool next(std::string& line) {
    line.clear();
    std::streambuf* b = in_.rdbuf();
    bool any = false;
    for (;;) {
      const int c = b->sbumpc();
      if (c == std::char_traits<char>::eof()) break;
      any = true;
      if (c == '\n') break;
      if (line.size() >= kMaxMeshLineBytes)
        throw VolumeError(where() + " a line longer than " + std::to_string(kMaxMeshLineBytes) + " bytes: not a mesh file");
      line.push_back(static_cast<char>(c));
    }
    if (!any) return false;
    ++number_;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
  }
  std::string where() const { return name_ + ":" + std::to_string(number_) + ":"; }

private:
  std::istream& in_;
  std::string name_;
  std::size_t number_;
};

double meshNumber(const std::string& word, const std::string& where, const char* what) {
  double v = 0.0;
  const char* end = word.data() + word.size();
  const auto [ptr, ec] = std::from_chars(word.data(), end, v);
  if (ec != std::errc() || ptr != end)
    throw VolumeError(where + " " + what + " '" + word + "' is not a number");
  if (!std::isfinite(v)) throw VolumeError(where + " " + what + " '" + word + "' is not a finite number");
  if (std::abs(v) > 1e9) throw VolumeError(where + " " + what + " " + word + " is beyond ±1e9");
  return v;
}

// Triangles gathered per part name, in the order the names first appear.
class MeshPartsBuilder {
public:
  explicit MeshPartsBuilder(std::string fallback) : fallback_(std::move(fallback)) {}
  void select(const std::string& name) { current_ = name.empty() ? fallback_ : name; }
  void add(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const std::string& where) {
    if (++triangles_ > kMaxMeshTriangles)
      throw VolumeError(where + " more than " + std::to_string(kMaxMeshTriangles) + " triangles: too many to voxelise");
    auto it = index_.find(current_);
    if (it == index_.end()) {
      if (names_.size() == kMaxMeshParts)
        throw VolumeError(where + " more than " + std::to_string(kMaxMeshParts) + " parts; MillSim voxelises at most that many");
      it = index_.emplace(current_, corners_.size()).first;
      names_.push_back(current_);
      corners_.emplace_back();
    }
    auto& c3 = corners_[it->second];
    c3.push_back(a), c3.push_back(b), c3.push_back(c);
  }
  std::vector<MeshPart> take();

private:
  std::string fallback_, current_ = fallback_;
  std::map<std::string, std::size_t> index_;
  std::vector<std::string> names_;
  std::vector<std::vector<glm::vec3>> corners_;
  std::uint64_t triangles_ = 0;
};

// Corners at one position become one vertex; triangles that lose a corner to
// it (zero area) are dropped.
MeshPart weldCorners(std::string name, const std::vector<glm::vec3>& corners) {
  struct Key {
    std::uint32_t x, y, z;
    bool operator==(const Key&) const = default;
  };
  struct Hash {
    std::size_t operator()(const Key& k) const {
      return (std::size_t(k.x) * 73856093u) ^ (std::size_t(k.y) * 19349663u) ^ (std::size_t(k.z) * 83492791u);
    }
  };
  // +0 and -0 are one position.
  auto bits = [](float f) { return std::bit_cast<std::uint32_t>(f == 0.f ? 0.f : f); };
  MeshPart part{std::move(name), {}, {}};
  std::unordered_map<Key, std::uint32_t, Hash> seen;
  seen.reserve(corners.size() / 2);
  std::uint32_t ids[3];
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const glm::vec3& p = corners[i];
    const auto [it, added] = seen.emplace(Key{bits(p.x), bits(p.y), bits(p.z)}, std::uint32_t(part.vertices.size()));
    if (added) part.vertices.push_back(p);
    ids[i % 3] = it->second;
    if (i % 3 == 2 && ids[0] != ids[1] && ids[1] != ids[2] && ids[0] != ids[2])
      part.triangles.emplace_back(ids[0], ids[1], ids[2]);
  }
  return part;
}

std::vector<MeshPart> MeshPartsBuilder::take() {
  std::vector<MeshPart> out;
  for (std::size_t i = 0; i < names_.size(); ++i) {
    out.push_back(weldCorners(names_[i], corners_[i]));
    std::vector<glm::vec3>().swap(corners_[i]);
  }
  return out;
}

glm::vec3 meshPoint(const std::vector<std::string>& w, std::size_t at, const std::string& where) {
  return glm::vec3(float(meshNumber(w[at], where, "coordinate")), float(meshNumber(w[at + 1], where, "coordinate")),
                   float(meshNumber(w[at + 2], where, "coordinate")));
}

// ---- STL ----

std::vector<MeshPart> readAsciiStl(std::istream& in, const std::string& name, const std::string& stem) {
  MeshLines lines(in, name);
  MeshPartsBuilder parts(stem);
  std::string line;
  std::vector<glm::vec3> loop;
  bool inFacet = false, anySolid = false;
  while (lines.next(line)) {
    const std::vector<std::string> w = words(line);
    if (w.empty()) continue;
    const std::string key = asciiLower(w[0]);
    if (key == "solid") {
      anySolid = true;
      std::string solid;
      for (std::size_t i = 1; i < w.size(); ++i) solid += (i > 1 ? " " : "") + w[i];
      parts.select(solid);
    } else if (key == "facet") {
      if (inFacet) throw VolumeError(lines.where() + " a facet begins inside another (no endfacet)");
      inFacet = true;
      loop.clear();
    } else if (key == "vertex") {
      if (!inFacet) throw VolumeError(lines.where() + " a vertex outside a facet");
      if (w.size() != 4) throw VolumeError(lines.where() + " a vertex needs three coordinates, found " + std::to_string(w.size() - 1));
      if (loop.size() == 3) throw VolumeError(lines.where() + " a facet with more than three vertices; STL facets are triangles");
      loop.push_back(meshPoint(w, 1, lines.where()));
    } else if (key == "endfacet") {
      if (!inFacet || loop.size() != 3)
        throw VolumeError(lines.where() + " a facet ends with " + std::to_string(loop.size()) + " vertices; expected 3");
      parts.add(loop[0], loop[1], loop[2], lines.where());
      inFacet = false;
    } else if (key != "outer" && key != "endloop" && key != "endsolid") {
      throw VolumeError(lines.where() + " '" + w[0] + "' is not an ASCII STL keyword (solid, facet, outer loop, vertex, endloop, endfacet, endsolid)");
    }
  }
  if (inFacet) throw VolumeError(lines.where() + " the file ends inside a facet");
  if (!anySolid) throw VolumeError(name + ": no 'solid' line: not an ASCII STL file");
  return parts.take();
}

std::vector<MeshPart> readBinaryStl(std::istream& in, std::uint32_t count, const std::string& name, const std::string& stem) {
  if (count > kMaxMeshTriangles)
    throw VolumeError(name + ": " + std::to_string(count) + " triangles, more than " + std::to_string(kMaxMeshTriangles) + " to voxelise");
  MeshPartsBuilder parts(stem);
  const std::string prefix = name + ":";
  char record[50];
  in.seekg(84);
  for (std::uint32_t i = 0; i < count; ++i) {
    if (!in.read(record, 50)) throw VolumeError(name + ": ends inside triangle " + std::to_string(i + 1));
    float f[12];
    std::memcpy(f, record, sizeof f);  // little-endian floats, as on every platform MillSim builds for
    for (int k = 3; k < 12; ++k)
      if (!std::isfinite(f[k]) || std::abs(f[k]) > 1e9f)
        throw VolumeError(name + ": triangle " + std::to_string(i + 1) + " has a coordinate that is not a finite number below 1e9");
    parts.add({f[3], f[4], f[5]}, {f[6], f[7], f[8]}, {f[9], f[10], f[11]}, prefix);
  }
  return parts.take();
}

// ---- OBJ ----

std::vector<MeshPart> readObj(std::istream& in, const std::string& name, const std::string& stem) {
  MeshLines lines(in, name);
  std::vector<glm::vec3> vertices;
  // Faces resolve after every vertex is read (a file may refer ahead); parts
  // keep their first-seen order. Flat: a face is a few numbers, not strings.
  struct Face {
    std::uint32_t part;
    std::uint32_t count;           // corners
    std::uint64_t first;           // into corners
    std::uint64_t verticesBefore;  // for negative (relative) corners
    std::uint64_t line;
  };
  std::vector<Face> faces;
  std::vector<long long> corners;  // as written: 1-based, or negative from the end
  std::vector<std::string> partNames{stem};
  std::map<std::string, std::uint32_t> partIndex{{stem, 0}};
  std::uint32_t part = 0;
  std::size_t lineNumber = 0;
  std::string line;
  std::uint64_t triangles = 0;
  while (lines.next(line)) {
    ++lineNumber;
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    const std::vector<std::string> w = words(line);
    if (w.empty()) continue;
    if (w[0] == "v") {
      if (w.size() < 4 || w.size() > 7) throw VolumeError(lines.where() + " a vertex needs three coordinates (x y z [w])");
      if (vertices.size() >= 3 * kMaxMeshTriangles) throw VolumeError(lines.where() + " too many vertices to voxelise");
      vertices.push_back(meshPoint(w, 1, lines.where()));
    } else if (w[0] == "f") {
      if (w.size() < 4) throw VolumeError(lines.where() + " a face needs at least three vertices");
      Face f{part, std::uint32_t(w.size() - 1), corners.size(), vertices.size(), lineNumber};
      for (std::size_t i = 1; i < w.size(); ++i) {
        const std::string first = w[i].substr(0, w[i].find('/'));  // v, v/vt, v//vn, v/vt/vn
        long long v = 0;
        const auto [ptr, ec] = std::from_chars(first.data(), first.data() + first.size(), v);
        if (ec != std::errc() || ptr != first.data() + first.size() || v == 0)
          throw VolumeError(lines.where() + " face vertex '" + w[i] + "' is not a vertex number (1, 2, … or −1 for the last)");
        corners.push_back(v);
      }
      triangles += f.count - 2;
      if (triangles > kMaxMeshTriangles)
        throw VolumeError(lines.where() + " more than " + std::to_string(kMaxMeshTriangles) + " triangles: too many to voxelise");
      faces.push_back(f);
    } else if (w[0] == "o" || w[0] == "g") {
      std::string n;
      for (std::size_t i = 1; i < w.size(); ++i) n += (i > 1 ? " " : "") + w[i];
      if (n.empty()) n = stem;
      const auto [it, added] = partIndex.emplace(n, std::uint32_t(partNames.size()));
      if (added) {
        if (partNames.size() == kMaxMeshParts)
          throw VolumeError(lines.where() + " more than " + std::to_string(kMaxMeshParts) + " groups; MillSim voxelises at most that many parts");
        partNames.push_back(n);
      }
      part = it->second;
    }
    // vt, vn, usemtl, mtllib, s, l, p and the rest carry nothing a solid needs.
  }
  MeshPartsBuilder parts(stem);
  const std::string prefix = name + ":";
  for (const Face& f : faces) {
    parts.select(partNames[f.part]);
    auto at = [&](long long v) {
      const long long i = v > 0 ? v - 1 : (long long)f.verticesBefore + v;
      if (i < 0 || i >= (long long)vertices.size())
        throw VolumeError(name + ":" + std::to_string(f.line) + ": face vertex " + std::to_string(v) +
                          " is out of range (the file has " + std::to_string(vertices.size()) + " vertices)");
      return vertices[std::size_t(i)];
    };
    const long long* c = corners.data() + f.first;
    const glm::vec3 a = at(c[0]);
    for (std::uint32_t i = 2; i < f.count; ++i) parts.add(a, at(c[i - 1]), at(c[i]), prefix);
  }
  if (faces.empty()) throw VolumeError(name + ": no faces ('f' lines): nothing to voxelise");
  return parts.take();
}

// ---- PLY ----

struct PlyProperty {
  std::string name;
  int bytes = 0;          // the value's, or the list's items'
  int countBytes = 0;     // a list's count; 0 for a plain property
  bool isFloat = false, isSigned = false;
  bool countSigned = false;
};

int plyTypeBytes(const std::string& t, bool& isFloat, bool& isSigned) {
  static const std::map<std::string, std::pair<int, int>> kTypes = {  // bytes, 0 unsigned / 1 signed / 2 float
      {"char", {1, 1}},   {"int8", {1, 1}},    {"uchar", {1, 0}},  {"uint8", {1, 0}},   {"short", {2, 1}},
      {"int16", {2, 1}},  {"ushort", {2, 0}},  {"uint16", {2, 0}}, {"int", {4, 1}},     {"int32", {4, 1}},
      {"uint", {4, 0}},   {"uint32", {4, 0}},  {"float", {4, 2}},  {"float32", {4, 2}}, {"double", {8, 2}},
      {"float64", {8, 2}}};
  const auto it = kTypes.find(t);
  if (it == kTypes.end()) return 0;
  isFloat = it->second.second == 2, isSigned = it->second.second == 1;
  return it->second.first;
}

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

double plyBinaryValue(const char* p, const PlyProperty& prop, int bytes, bool bigEndian) {
  char b[8];
  std::memcpy(b, p, std::size_t(bytes));
  if (bigEndian) std::reverse(b, b + bytes);
  if (prop.isFloat) {
    if (bytes == 4) {
      std::uint32_t u = 0;
      std::memcpy(&u, b, 4);
      return double(std::bit_cast<float>(u));
    }
    std::uint64_t u = 0;
    std::memcpy(&u, b, 8);
    return std::bit_cast<double>(u);
  }
  std::uint64_t u = 0;
  std::memcpy(&u, b, std::size_t(bytes));
  if (prop.isSigned && bytes < 8 && (u >> (8 * bytes - 1)) & 1u) u |= ~std::uint64_t(0) << (8 * bytes);
  return prop.isSigned ? double(std::int64_t(u)) : double(u);
}

std::vector<MeshPart> readPly(std::istream& in, std::uintmax_t fileBytes, const std::string& name, const std::string& stem) {
  HeaderLines header(in, name, "PLY", "an end_header line");
  std::string line;
  if (!header.next(line) || trim(line) != "ply") throw VolumeError(name + ": does not begin with 'ply': not a PLY file");
  std::string format;
  std::vector<PlyElement> elements;
  bool ended = false;
  std::size_t lineNo = 1;
  while (header.next(line)) {
    ++lineNo;
    const std::string where = name + ":" + std::to_string(lineNo) + ":";
    const std::vector<std::string> w = words(line);
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "end_header") {
      ended = true;
      break;
    }
    if (w[0] == "format") {
      if (w.size() != 3 || (w[1] != "ascii" && w[1] != "binary_little_endian" && w[1] != "binary_big_endian"))
        throw VolumeError(where + " format '" + line + "' is not ascii, binary_little_endian or binary_big_endian 1.0");
      format = w[1];
    } else if (w[0] == "element") {
      if (w.size() != 3) throw VolumeError(where + " an element line is 'element NAME COUNT'");
      PlyElement e{w[1], 0, {}};
      const auto [p, ec] = std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count);
      if (ec != std::errc() || p != w[2].data() + w[2].size()) throw VolumeError(where + " element count '" + w[2] + "' is not a whole number");
      elements.push_back(e);
    } else if (w[0] == "property") {
      if (elements.empty()) throw VolumeError(where + " a property before any element");
      PlyProperty prop;
      bool f = false, s = false;
      if (w.size() == 5 && w[1] == "list") {
        prop.countBytes = plyTypeBytes(w[2], f, s);
        prop.countSigned = s;
        if (prop.countBytes == 0 || f) throw VolumeError(where + " list count type '" + w[2] + "' is not an integer type");
        prop.bytes = plyTypeBytes(w[3], prop.isFloat, prop.isSigned);
        prop.name = w[4];
      } else if (w.size() == 3) {
        prop.bytes = plyTypeBytes(w[1], prop.isFloat, prop.isSigned);
        prop.name = w[2];
      }
      if (prop.bytes == 0) throw VolumeError(where + " property '" + line + "' has no PLY type (char, uchar, short, …, float, double)");
      elements.back().properties.push_back(prop);
    } else {
      throw VolumeError(where + " '" + w[0] + "' is not a PLY header keyword");
    }
  }
  if (!ended) throw VolumeError(name + ": the PLY header has no end_header line");
  if (format.empty()) throw VolumeError(name + ": the PLY header has no format line");
  const PlyElement* vertex = nullptr;
  const PlyElement* face = nullptr;
  for (const PlyElement& e : elements) {
    if (e.name == "vertex") vertex = &e;
    if (e.name == "face") face = &e;
  }
  if (!vertex || !face) throw VolumeError(name + ": a PLY mesh needs 'vertex' and 'face' elements");
  int xyz[3] = {-1, -1, -1}, indices = -1;
  for (std::size_t i = 0; i < vertex->properties.size(); ++i)
    for (int a = 0; a < 3; ++a)
      if (vertex->properties[i].name == std::string(1, "xyz"[a]) && vertex->properties[i].countBytes == 0) xyz[a] = int(i);
  for (std::size_t i = 0; i < face->properties.size(); ++i)
    if ((face->properties[i].name == "vertex_indices" || face->properties[i].name == "vertex_index") && face->properties[i].countBytes)
      indices = int(i);
  if (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0) throw VolumeError(name + ": the PLY vertex element has no x, y and z");
  if (indices < 0) throw VolumeError(name + ": the PLY face element has no vertex_indices list");
  if (face->properties[std::size_t(indices)].isFloat)
    throw VolumeError(name + ": the PLY face list '" + face->properties[std::size_t(indices)].name +
                      "' holds floating-point values; vertex indices are integers");
  // Every element takes a byte a value at least (ASCII: a digit and a space, two): refuse counts the file cannot hold.
  std::uint64_t least = 0;
  for (const PlyElement& e : elements) {
    if (e.count > 3 * kMaxMeshTriangles) throw VolumeError(name + ": " + std::to_string(e.count) + " " + e.name + " elements, too many to voxelise");
    least += e.count * std::max<std::size_t>(e.properties.size(), 1);
  }
  if (least > fileBytes) throw VolumeError(name + ": the PLY header declares more elements than the file's " + std::to_string(fileBytes) + " bytes hold");

  const bool ascii = format == "ascii", big = format == "binary_big_endian";
  std::vector<glm::vec3> vertices;
  MeshPartsBuilder parts(stem);
  MeshLines lines(in, name, lineNo);
  const std::string prefix = name + ":";
  std::vector<double> values;
  // One element's values: plain properties, then a list's items after its count.
  auto readElement = [&](const PlyElement& e, std::vector<double>& out, std::vector<long long>& list, int listProperty) {
    out.assign(e.properties.size(), 0.0);
    list.clear();
    if (ascii) {
      std::string l;
      if (!lines.next(l)) throw VolumeError(name + ": the PLY data ends before its " + e.name + " elements do");
      const std::vector<std::string> w = words(l);
      std::size_t at = 0;
      for (std::size_t p = 0; p < e.properties.size(); ++p) {
        if (at >= w.size()) throw VolumeError(lines.where() + " too few values for a " + e.name);
        const double v = meshNumber(w[at++], lines.where(), "value");
        if (!e.properties[p].countBytes) {
          out[p] = v;
          continue;
        }
        if (v < 0 || v > 1000 || v != std::floor(v))
          throw VolumeError(lines.where() + " a list of '" + w[at - 1] + "' items; expected a whole number up to 1000");
        for (int k = 0; k < int(v); ++k) {
          if (at >= w.size()) throw VolumeError(lines.where() + " too few values for a " + e.name);
          const double item = meshNumber(w[at++], lines.where(), "value");
          if (int(p) == listProperty && item != std::floor(item))
            throw VolumeError(lines.where() + " vertex index '" + w[at - 1] + "' is not a whole number");
          if (int(p) == listProperty) list.push_back((long long)item);
        }
      }
      return;
    }
    char buf[8];
    auto read = [&](int bytes) {
      if (!in.read(buf, bytes)) throw VolumeError(name + ": the PLY data ends before its " + e.name + " elements do");
    };
    for (std::size_t p = 0; p < e.properties.size(); ++p) {
      const PlyProperty& prop = e.properties[p];
      if (!prop.countBytes) {
        read(prop.bytes);
        out[p] = plyBinaryValue(buf, prop, prop.bytes, big);
        continue;
      }
      read(prop.countBytes);
      PlyProperty countType{prop.name, prop.countBytes, 0, false, prop.countSigned};
      const double n = plyBinaryValue(buf, countType, prop.countBytes, big);
      if (n < 0 || n > 1000) throw VolumeError(name + ": a " + e.name + " list of " + fmt(n) + " items; expected 0 to 1000");
      for (int k = 0; k < int(n); ++k) {
        read(prop.bytes);
        const double item = plyBinaryValue(buf, prop, prop.bytes, big);  // an integer type: finite, at most 2^64
        if (int(p) == listProperty) list.push_back(item > 1e18 ? -1 : (long long)item);
      }
    }
  };
  std::vector<long long> list;
  for (const PlyElement& e : elements) {
    for (std::uint64_t i = 0; i < e.count; ++i) {
      readElement(e, values, list, &e == face ? indices : -1);
      if (&e == vertex) {
        const glm::dvec3 p(values[std::size_t(xyz[0])], values[std::size_t(xyz[1])], values[std::size_t(xyz[2])]);
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || glm::length(p) > 1e9)
          throw VolumeError(name + ": vertex " + std::to_string(i) + " is not a finite point below 1e9");
        vertices.push_back(glm::vec3(p));
      } else if (&e == face) {
        if (list.size() < 3) throw VolumeError(name + ": face " + std::to_string(i) + " has fewer than three vertices");
        for (long long v : list)
          if (v < 0 || v >= (long long)vertices.size())
            throw VolumeError(name + ": face " + std::to_string(i) + " names vertex " + std::to_string(v) + " of " +
                              std::to_string(vertices.size()));
        for (std::size_t k = 2; k < list.size(); ++k)
          parts.add(vertices[std::size_t(list[0])], vertices[std::size_t(list[k - 1])], vertices[std::size_t(list[k])], prefix);
      }
    }
  }
  return parts.take();
}

}  // namespace

std::size_t SurfaceMesh::triangleCount() const {
  std::size_t n = 0;
  for (const MeshPart& p : parts) n += p.triangles.size();
  return n;
}

bool isMeshFile(const fs::path& file) {
  const std::string ext = asciiLower(file.extension().string());
  return ext == ".stl" || ext == ".obj" || ext == ".ply";
}

SurfaceMesh readSurfaceMesh(const fs::path& file) {
  requireFile(file, "a mesh file");
  const std::string name = file.string(), stem = file.stem().string();
  const std::string ext = asciiLower(file.extension().string());
  std::ifstream in(file, std::ios::binary);
  if (!in) throw VolumeError(name + ": cannot be opened");
  std::error_code ec;
  const std::uintmax_t bytes = fs::file_size(file, ec);
  SurfaceMesh mesh;
  if (ext == ".stl") {
    // Binary when the size is exactly what its count says (some binary
    // headers begin with "solid" too), else ASCII.
    char head[84] = {0};
    in.read(head, 84);
    std::uint32_t count = 0;
    std::memcpy(&count, head + 80, 4);
    if (in.gcount() == 84 && !ec && bytes == 84 + 50 * std::uintmax_t(count)) {
      mesh.format = "binary STL";
      mesh.parts = readBinaryStl(in, count, name, stem);
    } else if (std::string(head, std::size_t(std::min<std::streamsize>(in.gcount(), 5))) == "solid") {
      in.clear();
      in.seekg(0);
      mesh.format = "STL";
      mesh.parts = readAsciiStl(in, name, stem);
    } else {
      throw VolumeError(name + ": neither ASCII STL (it would begin with 'solid') nor binary STL (84 + 50 × " +
                        std::to_string(count) + " bytes, it has " + std::to_string(bytes) + ")");
    }
  } else if (ext == ".obj") {
    mesh.format = "OBJ";
    mesh.parts = readObj(in, name, stem);
  } else if (ext == ".ply") {
    mesh.format = "PLY";
    mesh.parts = readPly(in, bytes, name, stem);
  } else {
    throw VolumeError(name + ": not a mesh file (.stl, .obj, .ply)");
  }
  std::erase_if(mesh.parts, [](const MeshPart& p) { return p.triangles.empty(); });
  if (mesh.parts.empty()) throw VolumeError(name + ": no triangles with three distinct corners: nothing to voxelise");
  return mesh;
}

OpenEdges openEdges(const MeshPart& part) {
  // Directed edges as their triangles run; an edge is closed when the other
  // direction (a neighbour's) or a second use is there.
  std::unordered_map<std::uint64_t, int> uses;
  uses.reserve(part.triangles.size() * 3);
  auto key = [](std::uint32_t a, std::uint32_t b) { return (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b); };
  for (const glm::uvec3& t : part.triangles)
    for (int k = 0; k < 3; ++k) ++uses[key(t[k], t[(k + 1) % 3])];
  OpenEdges o;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> open;
  for (const glm::uvec3& t : part.triangles)
    for (int k = 0; k < 3; ++k)
      if (uses[key(t[k], t[(k + 1) % 3])] == 1) open.emplace_back(t[k], t[(k + 1) % 3]);
  o.count = open.size();
  if (open.empty()) return o;
  o.from = part.vertices[open[0].first], o.to = part.vertices[open[0].second];
  // Loops: open edges joined through shared vertices (union-find); each
  // loop's vector area ½ Σ a × b over its directed edges, and its length.
  std::unordered_map<std::uint32_t, std::uint32_t> parent;
  std::function<std::uint32_t(std::uint32_t)> find = [&](std::uint32_t v) {
    auto it = parent.find(v);
    if (it == parent.end()) return parent[v] = v;
    while (it->second != v) {
      const std::uint32_t up = it->second;
      parent[v] = parent[up];
      v = up;
      it = parent.find(v);
    }
    return v;
  };
  for (const auto& [a, b] : open) {
    const std::uint32_t ra = find(a), rb = find(b);
    if (ra != rb) parent[ra] = rb;
  }
  std::unordered_map<std::uint32_t, std::pair<glm::dvec3, double>> loops;  // root → (vector area, length)
  for (const auto& [a, b] : open) {
    const glm::dvec3 pa(part.vertices[a]), pb(part.vertices[b]);
    auto& l = loops[find(a)];
    l.first += 0.5 * glm::cross(pa, pb);
    l.second += glm::length(pb - pa);
  }
  // A hole's width as its hydraulic diameter, 4 × area / perimeter: a square
  // hole's side, a round one's diameter, a crack's gap (about 0 where faces meet).
  for (const auto& [root, l] : loops)
    if (l.second > 0.0) o.widestGap = std::max(o.widestGap, 4.0 * glm::length(l.first) / l.second);
  return o;
}

double enclosedVolume(const MeshPart& part) {
  double v = 0.0;
  for (const glm::uvec3& t : part.triangles)
    v += glm::dot(glm::dvec3(part.vertices[t.x]), glm::cross(glm::dvec3(part.vertices[t.y]), glm::dvec3(part.vertices[t.z])));
  return std::abs(v) / 6.0;
}

}  // namespace millsim
