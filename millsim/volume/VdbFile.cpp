// OpenVDB .vdb files: readVdb and writeVdb.
//
// The grid's index space is our index space (voxel (i, j, k) is grid coordinate
// (i, j, k)); its transform gives the voxel size in millimetres. Files written
// here hold one FloatGrid named "density" and the metadata "millsim_dims" (the
// volume's dimensions, which the active voxels alone cannot tell when the
// border is air).
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>

#include <poll.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Prune.h>

#include "millsim/volume/VdbStructureCheck.h"
#include "millsim/volume/VolumeIO.h"

namespace fs = std::filesystem;

namespace millsim {

namespace {

const char* const kDimsMeta = "millsim_dims";
// What one grid may take in memory: a dense float grid of kMaxVoxels is 4 GiB;
// twice that leaves room for the tree.
constexpr std::int64_t kMaxGridBytes = std::int64_t(kMaxVoxels) * 8;

std::string gridList(const openvdb::GridPtrVec& grids) {
  std::string s;
  for (const auto& g : grids) {
    if (!s.empty()) s += ", ";
    s += "'" + g->getName() + "' (" + g->valueType() + ")";
  }
  return s.empty() ? "none" : s;
}

void refuseOversizedGrid(const std::string& name, const openvdb::GridBase& grid) {
  const auto lo = grid.getMetadata<openvdb::Vec3IMetadata>(openvdb::GridBase::META_FILE_BBOX_MIN);
  const auto hi = grid.getMetadata<openvdb::Vec3IMetadata>(openvdb::GridBase::META_FILE_BBOX_MAX);
  if (lo && hi) {
    std::uint64_t voxels = 1;
    for (int a = 0; a < 3; ++a) {
      const std::int64_t extent = std::int64_t(hi->value()[a]) - std::int64_t(lo->value()[a]) + 1;
      voxels = extent <= 0 ? 0 : std::min<std::uint64_t>(voxels * std::uint64_t(extent), kMaxVoxels + 1);
    }
    if (voxels > kMaxVoxels) {
      std::ostringstream m;
      m << name << ": grid '" << grid.getName() << "' spans " << lo->value() << " to " << hi->value()
        << ", more than the limit of " << kMaxVoxels << " voxels";
      throw VolumeError(m.str());
    }
  }
  if (const auto mem = grid.getMetadata<openvdb::Int64Metadata>(openvdb::GridBase::META_FILE_MEM_BYTES);
      mem && mem->value() > kMaxGridBytes)
    throw VolumeError(name + ": grid '" + grid.getName() + "' needs " + std::to_string(mem->value()) +
                      " bytes in memory, more than the " + std::to_string(kMaxGridBytes) + " a volume may take");
}

// The volume's grid from the file's, clipped to the volume's box: active
// values as they are, inactive voxels the file's background; then, as
// VoxelVolume::fromDense does, values at or below air become inactive air.
// Tile by tile and leaf by leaf: copying through a dense array, as the other
// readers must, would take 4 bytes for every voxel of the box at once (46 MB
// for the full-size phantom, 400 MB and more for a 512² CT).
openvdb::FloatGrid::Ptr copyClipped(const openvdb::FloatGrid& file, glm::ivec3 dims, float air,
                                    const std::string& name) {
  using Tree = openvdb::FloatTree;
  using Leaf = Tree::LeafNodeType;
  const openvdb::CoordBBox box(openvdb::Coord(0), openvdb::Coord(dims.x - 1, dims.y - 1, dims.z - 1));
  const float background = file.background();
  if (!std::isfinite(background))
    throw VolumeError(name + ": grid '" + file.getName() + "' has the background value " + std::to_string(background) +
                      "; a density must be a finite number");
  auto out = openvdb::FloatGrid::create(air);
  out->setName("density");
  Tree& tree = out->tree();
  if (background > air) tree.fill(box, background, /*active=*/true);

  // Active tiles (every level above the leaves).
  Tree::ValueOnCIter tile = file.tree().cbeginValueOn();
  tile.setMaxDepth(Tree::ValueOnCIter::LEAF_DEPTH - 1);
  for (; tile; ++tile) {
    openvdb::CoordBBox b;
    tile.getBoundingBox(b);
    b.intersect(box);
    if (b.empty()) continue;
    const float v = *tile;
    if (!std::isfinite(v)) refuseNonFiniteDensity(name, v, b.min().x(), b.min().y(), b.min().z());
    if (v > air)
      tree.fill(b, v, true);
    else
      tree.fill(b, air, false);
  }

  // Leaves: every voxel of the box they hold is written.
  for (auto leaf = file.tree().cbeginLeaf(); leaf; ++leaf) {
    openvdb::CoordBBox b = leaf->getNodeBoundingBox();
    b.intersect(box);
    if (b.empty()) continue;
    Leaf* dst = tree.touchLeaf(leaf->origin());
    for (int i = b.min().x(); i <= b.max().x(); ++i)
      for (int j = b.min().y(); j <= b.max().y(); ++j)
        for (int k = b.min().z(); k <= b.max().z(); ++k) {
          const openvdb::Index o = Leaf::coordToOffset(openvdb::Coord(i, j, k));
          const float v = leaf->isValueOn(o) ? leaf->getValue(o) : background;
          if (!std::isfinite(v)) refuseNonFiniteDensity(name, v, i, j, k);
          if (v > air)
            dst->setValueOn(o, v);
          else
            dst->setValueOff(o, air);
        }
  }
  openvdb::tools::pruneInactive(tree);
  return out;
}

// Every grid of the file, read now. The statistics OpenVDB writes with every
// grid (bounding box, memory) are read without the trees, so a grid far
// larger than a volume may be is refused before its tree is allocated. A file
// without them (or one that lies) is still bounded by the voxel-count check.
openvdb::GridPtrVecPtr readGrids(const std::string& name) {
  try {
    openvdb::io::File f(name);
    f.open(/*delayLoad=*/false);  // read everything now, so that a bad file fails here
    const openvdb::GridPtrVecPtr described = f.readAllGridMetadata();  // kept: the loop must not outlive it
    for (const auto& g : *described) refuseOversizedGrid(name, *g);
    openvdb::GridPtrVecPtr grids = f.getGrids();
    f.close();
    return grids;
  } catch (const VolumeError&) {
    throw;
  } catch (const std::exception& e) {
    throw VolumeError(name + ": cannot read as an OpenVDB file: " + e.what());
  }
}

// OpenVDB 10 reads a chunk that the file marks as stored uncompressed into
// its buffer before it compares the chunk's size with the buffer's
// (io/Compression.cc, bloscFromStream and unzipFromStream): a corrupt size
// writes past the buffer, and the process crashed later (found by mutating a
// small .vdb; under the release build a segmentation fault at exit). So a
// child process reads the file first, with its memory and CPU time bounded;
// this process reads it only after the child has read it whole. A child that
// fails passes its error up a pipe; one that crashes or is stopped by its
// limits makes the file refused. About 1 ms for the fork and one more read
// of the file (20 ms for the full-size phantom).
void readInAChildFirst(const std::string& name) {
  int fds[2];
  if (pipe(fds) != 0) throw VolumeError(name + ": cannot check the file (pipe: " + std::strerror(errno) + ")");
  std::error_code ec;
  const std::uintmax_t bytes = fs::file_size(name, ec);
  // The child's address space: what this process maps now (read before the
  // fork), plus what a volume's grid may take and a margin.
  long pages = 0;
  if (std::FILE* statm = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(statm, "%ld", &pages) != 1) pages = 0;
    std::fclose(statm);
  }
  const rlim_t addressSpace = rlim_t(pages) * rlim_t(sysconf(_SC_PAGESIZE)) + rlim_t(kMaxGridBytes) + (rlim_t(1) << 30);
  const int seconds = 60 + int(ec ? 0 : std::min<std::uintmax_t>(bytes >> 20, 1 << 20));
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]), close(fds[1]);
    throw VolumeError(name + ": cannot check the file (fork: " + std::strerror(errno) + ")");
  }
  if (pid == 0) {  // the child: read, report, and leave without running anything of the parent's
    close(fds[0]);
    // A minute of CPU time and a second per megabyte read is far above a real
    // file's need; a grid may take up to kMaxGridBytes (refuseOversizedGrid).
    rlimit cpu{};
    cpu.rlim_cur = cpu.rlim_max = rlim_t(seconds);
    setrlimit(RLIMIT_CPU, &cpu);
    if (pages > 0) {  // without /proc the current size is unknown: no limit rather than a wrong one
      rlimit as{};
      as.rlim_cur = as.rlim_max = addressSpace;
      setrlimit(RLIMIT_AS, &as);
    }
    int code = 0;
    std::string message;
    try {
      readGrids(name);
    } catch (const std::exception& e) {
      message = e.what(), code = 1;
    } catch (...) {
      message = name + ": cannot read as an OpenVDB file", code = 1;
    }
    for (std::size_t at = 0; at < message.size();) {
      const ssize_t n = write(fds[1], message.data() + at, message.size() - at);
      if (n <= 0) break;
      at += std::size_t(n);
    }
    _exit(code);
  }
  close(fds[1]);
  // Wall-clock time too: a child that waits (on a lock another thread of this
  // process held at the fork) uses no CPU time and would never be stopped.
  std::string message;
  char buffer[4096];
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
  bool late = false;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    pollfd p{fds[0], POLLIN, 0};
    const int ready = left.count() > 0 ? poll(&p, 1, int(std::min<long long>(left.count(), 1 << 30))) : 0;
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) {
      late = ready == 0;
      break;
    }
    const ssize_t n = read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    message.append(buffer, std::size_t(n));
  }
  close(fds[0]);
  if (late) kill(pid, SIGKILL);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return;
  if (WIFEXITED(status) && WEXITSTATUS(status) == 1 && !message.empty()) throw VolumeError(message);
  const int signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  const std::string what =
      late                ? "did not finish within " + std::to_string(seconds) + " s"
      : signal == SIGXCPU ? "used more than " + std::to_string(seconds) + " s of CPU time"
      : signal != 0       ? "crashed on it (signal " + std::to_string(signal) + ", " + strsignal(signal) + ")"
                          : "stopped with status " + std::to_string(WEXITSTATUS(status));
  throw VolumeError(name + ": corrupt OpenVDB file: OpenVDB's reader " + what +
                    " (it was read in a separate process first)");
}

}  // namespace

VoxelVolume readVdb(const fs::path& file, float airValue) {
  const std::string name = file.string();
  requireFile(file, "a .vdb file");
  checkVdbStructure(file, name);  // before OpenVDB trusts the file's counts and lengths
  openvdb::initialize();

  readInAChildFirst(name);
  const openvdb::GridPtrVecPtr grids = readGrids(name);

  // The grid named "density" if it is a FloatGrid, else the first FloatGrid.
  openvdb::FloatGrid::Ptr grid;
  for (const auto& g : *grids)
    if (g->getName() == "density" && g->isType<openvdb::FloatGrid>()) grid = openvdb::gridPtrCast<openvdb::FloatGrid>(g);
  for (const auto& g : *grids)
    if (!grid && g->isType<openvdb::FloatGrid>()) grid = openvdb::gridPtrCast<openvdb::FloatGrid>(g);
  if (!grid) throw VolumeError(name + ": no float grid in the file (grids: " + gridList(*grids) + ")");

  if (!grid->transform().isLinear())
    throw VolumeError(name + ": grid '" + grid->getName() + "' has a non-linear (frustum) transform; only linear transforms are supported");
  const openvdb::Vec3d vs = grid->voxelSize();  // millimetres
  glm::dvec3 spacingMm(vs.x(), vs.y(), vs.z());
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(spacingMm[a]) || spacingMm[a] <= 0.0) {
      std::ostringstream m;
      m << name << ": voxel spacing along " << "xyz"[a] << " is " << spacingMm[a]
        << " mm; spacing must be a positive finite number of millimetres";
      throw VolumeError(m.str());
    }

  glm::ivec3 dims;
  if (auto meta = grid->getMetadata<openvdb::Vec3IMetadata>(kDimsMeta)) {
    const openvdb::Vec3i d = meta->value();
    dims = glm::ivec3(d.x(), d.y(), d.z());
  } else {
    const openvdb::CoordBBox box = grid->evalActiveVoxelBoundingBox();
    if (box.empty())
      throw VolumeError(name + ": grid '" + grid->getName() + "' has no active voxels and no " + kDimsMeta +
                        " metadata, so its dimensions are unknown");
    if (box.min().x() < 0 || box.min().y() < 0 || box.min().z() < 0) {
      std::ostringstream m;
      m << name << ": grid '" << grid->getName() << "' has active voxels at negative indices (bounding box " << box
        << "); the volume must start at index (0, 0, 0)";
      throw VolumeError(m.str());
    }
    dims = glm::ivec3(box.max().x() + 1, box.max().y() + 1, box.max().z() + 1);
  }
  const glm::dvec3 spacing = spacingMm / 1000.0;
  checkVolumeShape(name, dims, spacing);

  return VoxelVolume(copyClipped(*grid, dims, airValue, name), dims, spacing, airValue);
}

void writeVdb(const VoxelVolume& volume, const fs::path& file) {
  const std::string name = file.string();
  openvdb::initialize();
  // A new grid sharing the volume's tree: the volume itself is not touched.
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(volume.gridPtr()->treePtr());
  grid->setName("density");
  const glm::dvec3 mm = volume.voxelSize() * 1000.0;
  auto xform = openvdb::math::Transform::createLinearTransform(1.0);
  xform->preScale(openvdb::Vec3d(mm.x, mm.y, mm.z));
  grid->setTransform(xform);
  const glm::ivec3 d = volume.dims();
  grid->insertMeta(kDimsMeta, openvdb::Vec3IMetadata(openvdb::Vec3i(d.x, d.y, d.z)));
  try {
    openvdb::io::File f(name);
    f.write(openvdb::GridCPtrVec{grid});
    f.close();
  } catch (const std::exception& e) {
    throw VolumeError(name + ": cannot write the OpenVDB file: " + e.what());
  }
}

}  // namespace millsim
