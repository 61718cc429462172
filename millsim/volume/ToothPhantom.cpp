#include "millsim/volume/ToothPhantom.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <memory>
#include <vector>

#include <openvdb/openvdb.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace millsim {

namespace {

// All geometry is in millimetres, in the tooth frame: the volume's centre is
// the origin, +Y runs from the root apices to the occlusal surface.
constexpr double kCej = 2.0;  // cemento-enamel junction height
constexpr double kCementumThickness = 0.15;  // cementum on the root (about 0.05–0.2 mm)

double smin(double a, double b, double k) {  // smooth union of two distances
  const double h = std::clamp(0.5 + 0.5 * (b - a) / k, 0.0, 1.0);
  return b + (a - b) * h - k * h * (1.0 - h);
}

double sphere(const glm::dvec3& p, const glm::dvec3& c, double r) { return glm::length(p - c) - r; }

// Approximate distance to an axis-aligned superellipsoid: exact on the axes,
// good enough elsewhere because it only shapes a one-voxel anti-aliasing ramp.
double superellipsoid(const glm::dvec3& p, const glm::dvec3& c, const glm::dvec3& r, double e) {
  const glm::dvec3 q = glm::abs(p - c) / r;
  const double xz = std::pow(std::pow(q.x, e) + std::pow(q.z, e), 2.0 / e);
  const double f = std::sqrt(xz + q.y * q.y);
  return (f - 1.0) * std::min({r.x, r.y, r.z});
}

// A cone with rounded ends from a (radius ra) to b (radius rb).
double roundCone(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, double ra, double rb) {
  const glm::dvec3 ab = b - a;
  const double t = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
  return glm::length(p - (a + t * ab)) - (ra + (rb - ra) * t);
}

double box(const glm::dvec3& p, const glm::dvec3& c, const glm::dvec3& half) {
  const glm::dvec3 q = glm::abs(p - c) - half;
  return glm::length(glm::max(q, 0.0)) + std::min(std::max({q.x, q.y, q.z}), 0.0);
}

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// The whole tooth: crown with four cusps, a cervical trunk, two diverging roots.
double toothDistance(const glm::dvec3& p) {
  double crown = superellipsoid(p, {0, 5.2, 0}, {5.3, 3.8, 4.8}, 2.6);
  for (double sx : {-1.0, 1.0})
    for (double sz : {-1.0, 1.0}) crown = smin(crown, sphere(p, {2.3 * sx, 7.6, 2.0 * sz}, 2.0), 1.2);
  const double trunk = roundCone(p, {0, 2.5, 0}, {0, -0.5, 0}, 4.1, 3.4);
  const double mesial = roundCone(p, {-2.3, 0.5, 0}, {-3.0, -10.2, 0.2}, 2.0, 0.55);
  const double distal = roundCone(p, {2.3, 0.5, 0}, {2.8, -9.8, -0.2}, 2.0, 0.55);
  return smin(smin(crown, trunk, 1.0), smin(mesial, distal, 0.6), 1.0);
}

double pulpDistance(const glm::dvec3& p) {
  double pulp = superellipsoid(p, {0, 3.6, 0}, {2.5, 1.5, 2.1}, 2.2);
  for (double sx : {-1.0, 1.0})
    for (double sz : {-1.0, 1.0}) pulp = smin(pulp, sphere(p, {1.7 * sx, 5.0, 1.4 * sz}, 0.7), 0.6);
  const double canal1 = roundCone(p, {-2.0, 2.5, 0}, {-2.95, -9.7, 0.2}, 0.45, 0.12);
  const double canal2 = roundCone(p, {2.0, 2.5, 0}, {2.75, -9.3, -0.2}, 0.45, 0.12);
  return smin(pulp, std::min(canal1, canal2), 0.5);
}

// Enamel covers the crown, thinning to nothing at the cemento-enamel junction.
double enamelThickness(double y) { return 1.4 * smoothstep(kCej - 0.5, kCej + 2.5, y); }

// Fraction of a voxel of size h (mm) inside a surface at signed distance d.
double coverage(double d, double h) { return std::clamp(0.5 - d / h, 0.0, 1.0); }

// The density at p (mm) for a voxel of size h (mm), given the tooth's and the
// pulp's distances there (each computed once when labels are made too: their
// pow() calls were a fifth of a 25 µm lesson's opening).
float densityAt(const glm::dvec3& pmm, double tooth, double pulp, bool socket, double hmm) {
  using D = ToothDensities;
  double v = D::air;
  if (socket) {
    // Alveolar bone up to 1.5 mm below the junction, with a 0.2 mm ligament
    // space around the roots.
    const double bone = box(pmm, {0, -6.0, 0}, {9.5, 6.5, 7.0});
    v += (D::bone - v) * coverage(bone, hmm);
    v += (D::softTissue - v) * coverage(std::max(tooth - 0.2, bone), hmm);
  }
  const double enamel = enamelThickness(pmm.y);
  auto material = [&](double dentinDepth) {
    double m = D::enamel;
    m += (D::dentin - m) * coverage(tooth + enamel - dentinDepth, hmm);
    return m + (D::softTissue - m) * coverage(pulp, hmm);
  };
  const double c = coverage(tooth, hmm);
  return static_cast<float>(v + ((c < 1.0 ? material(hmm) : material(0.0)) - v) * c);
}

float densityAt(const glm::dvec3& pmm, bool socket, double hmm) {
  return densityAt(pmm, toothDistance(pmm), pulpDistance(pmm), socket, hmm);
}

// The tissue a voxel of size h (mm) at p is mostly made of, by the same
// layering as densityAt: every voxel densityAt gives material to (its centre
// within half a voxel of a surface) gets a label, so the label volume covers
// the density volume's material voxel for voxel. `pulp()` gives the pulp's
// distance (only needed inside the tooth).
template <class Pulp> int labelAt(const glm::dvec3& pmm, double tooth, Pulp&& pulp, bool socket, double hmm) {
  const double reach = 0.5 * hmm;
  if (tooth < reach) {
    if (pulp() < 0.0) return kToothPulp;
    if (tooth + enamelThickness(pmm.y) < 0.0) {
      // Below the junction the root's outer layer is cementum.
      return pmm.y < kCej && tooth > -kCementumThickness ? kToothCementum : kToothDentin;
    }
    return pmm.y < kCej - 0.5 ? kToothCementum : kToothEnamel;
  }
  if (socket && box(pmm, {0, -6.0, 0}, {9.5, 6.5, 7.0}) < reach) return tooth - 0.2 < 0.0 ? kToothLigament : kToothBone;
  return 0;
}

int labelAt(const glm::dvec3& pmm, bool socket, double hmm) {
  return labelAt(pmm, toothDistance(pmm), [&] { return pulpDistance(pmm); }, socket, hmm);
}

// A voxel's position in the tooth frame (mm); the same arithmetic everywhere.
glm::dvec3 voxelPosition(const ToothPhantomOptions& o, glm::ivec3 ijk) {
  const double hmm = o.voxelSize * 1000.0;
  const glm::dvec3 half = (glm::dvec3(o.dims) - 1.0) * 0.5;
  return {(ijk.x - half.x) * hmm, (ijk.y - half.y) * hmm, (ijk.z - half.z) * hmm};
}

// Far outside the tooth (and its socket) there is only air: skip the geometry.
bool farFromTheTooth(const ToothPhantomOptions& o, const glm::dvec3& p) {
  return !o.socket && (std::abs(p.x) > 7.5 || std::abs(p.z) > 6.5 || p.y > 11.0 || p.y < -11.5);
}

// Whether no voxel of a block can hold material: its centre farther from the
// tooth (and the socket's bone) than the block's half-diagonal reaches. The
// tooth's distance is not exact (smooth unions, superellipsoids, round cones)
// but is a lower bound outside with a Lipschitz constant under 1.15 (the
// cones' radius slope), so 1.5 × the half-diagonal plus a voxel (material
// reaches half a voxel out: coverage and labels) is safe.
bool blockIsAir(const ToothPhantomOptions& o, const glm::dvec3& centre, double halfDiagonal) {
  const double hmm = o.voxelSize * 1000.0, reach = 1.5 * halfDiagonal + hmm;
  if (toothDistance(centre) <= reach) return false;
  return !o.socket || box(centre, {0, -6.0, 0}, {9.5, 6.5, 7.0}) > halfDiagonal + hmm;
}

// A block deep inside one tissue, far from every surface its value depends
// on, has one value: each coverage there is exactly 0 or 1, so every voxel's
// arithmetic gives the same number, and so does the block's centre's. The
// margins are the distances' Lipschitz bounds (under 1.15; the enamel's
// boundary tooth + enamelThickness(y) under 1.85) times the half-diagonal,
// plus a voxel. Empty when the block is not so.
struct DeepInside {
  bool inside = false;
  bool enamelSide = false;  // tooth + enamelThickness ≥ 0 throughout
};
DeepInside deepInside(const ToothPhantomOptions& o, const glm::dvec3& c, double halfDiagonal) {
  const double hmm = o.voxelSize * 1000.0, margin = 1.5 * halfDiagonal + hmm;
  const double tooth = toothDistance(c);
  // Past the cementum's 0.15 mm too: the labels' root layer.
  if (!(tooth < -(margin + kCementumThickness))) return {};
  if (!(pulpDistance(c) > margin)) return {};
  const double dd = tooth + enamelThickness(c.y);
  if (!(std::abs(dd) > 2.0 * halfDiagonal + hmm)) return {};
  // The labels' enamel/cementum split at the junction, and the socket's bone box.
  if (dd > 0.0 && !(std::abs(c.y - (kCej - 0.5)) > halfDiagonal + hmm)) return {};
  if (o.socket && !(std::abs(box(c, {0, -6.0, 0}, {9.5, 6.5, 7.0})) > halfDiagonal + hmm)) return {};
  return {true, dd > 0.0};
}

// Fills voxels lo..hi (inclusive) of each channel (densities, labels, or both
// from one evaluation of the distances): nothing where no voxel can hold
// material, one value where the block is deep inside one tissue, else halves
// (down to 2³ voxels, then voxel by voxel). `value(p, h)` gives a voxel's
// channels, `at(c, v)` stores them as voxel c's.
template <class F, class At>
void fillBlock(const ToothPhantomOptions& o, glm::ivec3 lo, glm::ivec3 hi, F& value, At&& at) {
  const double hmm = o.voxelSize * 1000.0;
  const glm::dvec3 centre = 0.5 * (voxelPosition(o, lo) + voxelPosition(o, hi));
  const double halfDiagonal = 0.5 * hmm * glm::length(glm::dvec3(hi - lo));
  if (blockIsAir(o, centre, halfDiagonal)) return;
  if (deepInside(o, centre, halfDiagonal).inside) {
    const auto v = value(centre, hmm);
    for (int k = lo.z; k <= hi.z; ++k)
      for (int j = lo.y; j <= hi.y; ++j)
        for (int i = lo.x; i <= hi.x; ++i) at(openvdb::Coord(i, j, k), v);
    return;
  }
  const glm::ivec3 size = hi - lo + 1;
  if (size.x > 2 || size.y > 2 || size.z > 2) {
    const glm::ivec3 mid = lo + (size + 1) / 2;  // the first voxel of the upper halves
    for (int c = 0; c < 8; ++c) {
      const glm::ivec3 a((c & 1) ? mid.x : lo.x, (c & 2) ? mid.y : lo.y, (c & 4) ? mid.z : lo.z);
      const glm::ivec3 b((c & 1) ? hi.x : mid.x - 1, (c & 2) ? hi.y : mid.y - 1, (c & 4) ? hi.z : mid.z - 1);
      if (a.x <= b.x && a.y <= b.y && a.z <= b.z) fillBlock(o, a, b, value, at);
    }
    return;
  }
  for (int k = lo.z; k <= hi.z; ++k)
    for (int j = lo.y; j <= hi.y; ++j)
      for (int i = lo.x; i <= hi.x; ++i) {
        const glm::dvec3 p = voxelPosition(o, {i, j, k});
        if (farFromTheTooth(o, p)) continue;
        const auto v = value(p, hmm);
        for (float x : v)
          if (!std::isfinite(x)) throw VolumeError("phantom:tooth: a non-finite value (a bug in the phantom)");
        at(openvdb::Coord(i, j, k), v);
      }
}

// Builds N sparse grids by a pure function of each voxel's position (N
// channels: `value` returns std::array<float, N>), a leaf (8³ voxels) at a time
// on TBB's threads: only blocks that may hold material are computed (a block
// deep inside one tissue by its centre alone), and no dense copy of the box is
// ever made (at 25 µm the box is 738 M voxels, 3 GB of floats, the tooth a
// tenth of it). Values at or below the channel's `outside` stay background, as
// VolumeBuilder stores them: any split over threads gives the same grids, and
// a channel's grid is the same whether it is built alone or with others.
template <std::size_t N, class F>
std::vector<VoxelVolume> fillPhantom(const ToothPhantomOptions& o, const std::array<float, N>& outside,
                                     const std::array<const char*, N>& names, F&& value) {
  using Leaf = VoxelVolume::Grid::TreeType::LeafNodeType;
  constexpr int kLeaf = int(Leaf::DIM);
  const glm::ivec3 n = o.dims, blocks = (n + kLeaf - 1) / kLeaf;
  const std::size_t nBlocks = std::size_t(blocks.x) * blocks.y * blocks.z;
  std::array<std::vector<std::unique_ptr<Leaf>>, N> leaves;
  for (auto& l : leaves) l.resize(nBlocks);
  tbb::parallel_for(0, blocks.z, [&](int bz) {
    std::array<std::array<float, Leaf::SIZE>, N> values;
    for (int by = 0; by < blocks.y; ++by)
      for (int bx = 0; bx < blocks.x; ++bx) {
        const glm::ivec3 lo = glm::ivec3(bx, by, bz) * kLeaf, hi = glm::min(lo + kLeaf, n) - 1;
        for (std::size_t c = 0; c < N; ++c) values[c].fill(outside[c]);
        fillBlock(o, lo, hi, value, [&](const openvdb::Coord& at, const std::array<float, N>& v) {
          const openvdb::Index i = Leaf::coordToOffset(at);
          for (std::size_t c = 0; c < N; ++c) values[c][i] = v[c];
        });
        const std::size_t b = (std::size_t(bz) * blocks.y + by) * blocks.x + bx;
        for (std::size_t c = 0; c < N; ++c) {
          std::unique_ptr<Leaf> leaf;
          for (openvdb::Index i = 0; i < Leaf::SIZE; ++i)
            if (values[c][i] > outside[c]) {
              if (!leaf) leaf = std::make_unique<Leaf>(openvdb::Coord(lo.x, lo.y, lo.z), outside[c], false);
              leaf->setValueOn(i, values[c][i]);
            }
          leaves[c][b] = std::move(leaf);
        }
      }
  });
  openvdb::initialize();  // idempotent and thread-safe
  std::vector<VoxelVolume> out;
  for (std::size_t c = 0; c < N; ++c) {
    VoxelVolume::Grid::Ptr grid = VoxelVolume::Grid::create(outside[c]);
    grid->setName(names[c]);  // as VolumeBuilder names the grids the readers make
    for (auto& leaf : leaves[c])
      if (leaf) grid->tree().addLeaf(leaf.release());
    out.emplace_back(grid, n, glm::dvec3(o.voxelSize), outside[c]);
  }
  return out;
}

}  // namespace

float toothPhantomDensity(const glm::dvec3& p, bool socket) { return densityAt(p * 1000.0, socket, 1e-9); }

ToothPhantomOptions parsePhantomUrl(const std::string& url) {
  const std::string prefix = "phantom:tooth";
  if (url.rfind(prefix, 0) != 0)
    throw VolumeError(url + ": unknown phantom; the embedded phantom is 'phantom:tooth'");
  ToothPhantomOptions o;
  std::string rest = url.substr(prefix.size());
  if (rest.empty()) return o;
  if (rest[0] != '?') throw VolumeError(url + ": expected '?' before phantom options");
  bool voxelGiven = false;
  std::size_t pos = 1;
  while (pos <= rest.size()) {
    std::size_t end = rest.find('&', pos);
    if (end == std::string::npos) end = rest.size();
    const std::string item = rest.substr(pos, end - pos);
    pos = end + 1;
    if (item.empty()) continue;
    const std::size_t eq = item.find('=');
    const std::string key = item.substr(0, eq), value = eq == std::string::npos ? "" : item.substr(eq + 1);
    auto number = [&](std::string_view s, double& out) {
      auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
      if (ec != std::errc() || p != s.data() + s.size() || !std::isfinite(out))
        throw VolumeError(url + ": option '" + key + "' expects a number, found '" + std::string(s) + "'");
    };
    if (key == "size") {
      double d[3];
      std::size_t a = 0;
      for (int i = 0; i < 3; ++i) {
        std::size_t b = value.find(',', a);
        if ((i < 2) == (b == std::string::npos))
          throw VolumeError(url + ": option 'size' expects three integers X,Y,Z, found '" + value + "'");
        number(std::string_view(value).substr(a, (b == std::string::npos ? value.size() : b) - a), d[i]);
        a = b + 1;
      }
      o.dims = glm::ivec3(int(d[0]), int(d[1]), int(d[2]));
      if (glm::dvec3(o.dims) != glm::dvec3(d[0], d[1], d[2]))
        throw VolumeError(url + ": option 'size' expects whole numbers, found '" + value + "'");
    } else if (key == "voxel") {
      number(value, o.voxelSize);
      voxelGiven = true;
    } else if (key == "socket") {
      if (value != "0" && value != "1") throw VolumeError(url + ": option 'socket' expects 0 or 1");
      o.socket = value == "1";
    } else {
      throw VolumeError(url + ": unknown phantom option '" + key + "' (expected size, voxel or socket)");
    }
  }
  // Without an explicit voxel size, keep the physical extent of the default volume.
  if (!voxelGiven && o.dims.x > 0) o.voxelSize = ToothPhantomOptions{}.voxelSize * 256.0 / o.dims.x;
  checkVolumeShape(url, o.dims, glm::dvec3(o.voxelSize));
  return o;
}

VoxelVolume makeToothPhantom(const ToothPhantomOptions& o) {
  checkVolumeShape("phantom:tooth", o.dims, glm::dvec3(o.voxelSize));
  return std::move(fillPhantom<1>(o, {ToothDensities::air}, {"density"}, [&](const glm::dvec3& p, double hmm) {
                     return std::array<float, 1>{densityAt(p, o.socket, hmm)};
                   }).front());
}

VoxelVolume makeToothPhantomLabels(const ToothPhantomOptions& o) {
  checkVolumeShape("phantom:tooth-labels", o.dims, glm::dvec3(o.voxelSize));
  return std::move(fillPhantom<1>(o, {0.f}, {"density"}, [&](const glm::dvec3& p, double hmm) {
                     return std::array<float, 1>{float(labelAt(p, o.socket, hmm))};
                   }).front());
}

ToothPhantomWithLabels makeToothPhantomWithLabels(const ToothPhantomOptions& o) {
  checkVolumeShape("phantom:tooth", o.dims, glm::dvec3(o.voxelSize));
  std::vector<VoxelVolume> both =
      fillPhantom<2>(o, {ToothDensities::air, 0.f}, {"density", "density"}, [&](const glm::dvec3& p, double hmm) {
        const double tooth = toothDistance(p), pulp = pulpDistance(p);
        return std::array<float, 2>{densityAt(p, tooth, pulp, o.socket, hmm),
                                    float(labelAt(p, tooth, [pulp] { return pulp; }, o.socket, hmm))};
      });
  return {std::move(both[0]), std::move(both[1])};
}

float toothPhantomVoxel(const ToothPhantomOptions& o, glm::ivec3 ijk) {
  const glm::dvec3 p = voxelPosition(o, ijk);
  return farFromTheTooth(o, p) ? ToothDensities::air : densityAt(p, o.socket, o.voxelSize * 1000.0);
}

int toothPhantomLabelVoxel(const ToothPhantomOptions& o, glm::ivec3 ijk) {
  const glm::dvec3 p = voxelPosition(o, ijk);
  return farFromTheTooth(o, p) ? 0 : labelAt(p, o.socket, o.voxelSize * 1000.0);
}

namespace {
const std::string kLabelsPrefix = "phantom:tooth-labels";

// Runs f, saying a VolumeError of the density url (what parsePhantomUrl and
// the shape check name) with the labels url the author wrote.
template <class F> auto namingTheLabelsUrl(const std::string& url, F&& f) {
  try {
    return f();
  } catch (const VolumeError& e) {
    std::string m = e.what();
    if (m.rfind("phantom:tooth", 0) == 0) m = url + m.substr(m.find(':', 8));
    throw VolumeError(m);
  }
}
}  // namespace

bool isPhantomLabelsUrl(const std::string& url) { return url.rfind(kLabelsPrefix, 0) == 0; }

ToothPhantomOptions parsePhantomLabelsUrl(const std::string& url) {
  if (!isPhantomLabelsUrl(url)) throw VolumeError(url + ": not a phantom label url (expected " + kLabelsPrefix + ")");
  return namingTheLabelsUrl(url, [&] { return parsePhantomUrl("phantom:tooth" + url.substr(kLabelsPrefix.size())); });
}

VoxelVolume loadPhantomLabels(const std::string& url) {
  const ToothPhantomOptions o = parsePhantomLabelsUrl(url);
  return namingTheLabelsUrl(url, [&] { return makeToothPhantomLabels(o); });
}

}  // namespace millsim
