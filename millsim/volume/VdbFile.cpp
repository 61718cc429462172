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
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <dlfcn.h>
#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Prune.h>

#include "millsim/volume/VdbGrids.h"
#include "millsim/volume/VdbStructureCheck.h"
#include "millsim/volume/VolumeIO.h"

namespace fs = std::filesystem;

namespace millsim {

namespace {

const char* const kDimsMeta = "millsim_dims";

std::string gridList(const openvdb::GridPtrVec& grids) {
  std::string s;
  for (const auto& g : grids) {
    if (!s.empty()) s += ", ";
    s += "'" + g->getName() + "' (" + g->valueType() + ")";
  }
  return s.empty() ? "none" : s;
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

// OpenVDB 10 reads a chunk that the file marks as stored uncompressed into
// its buffer before it compares the chunk's size with the buffer's
// (io/Compression.cc, bloscFromStream and unzipFromStream): a corrupt size
// writes past the buffer, and the process crashed later (found by mutating a
// small .vdb; under the release build a segmentation fault at exit). So
// millsim-vdb-probe (VdbProbeMain.cpp), a process of its own with its memory
// and CPU time bounded, reads the file first; this process reads it only after
// the probe has read it whole. A probe that fails passes its error up a pipe;
// one that crashes, is stopped by its limits or outlives the wall-clock limit
// makes the file refused. It is spawned, not forked: a forked copy of this
// process would hold every lock its other threads held at the fork (CI saw
// one wait a minute). About 70 ms to start the probe (it loads OpenVDB), and
// one more read of the file: 0.10 s in all for the full-size phantom.

// Where the probe is: MILLSIM_VDB_PROBE, else next to libmillsim (the build
// tree), else in the install's libexec folder relative to it.
std::vector<fs::path> probeCandidates() {
  if (const char* env = std::getenv("MILLSIM_VDB_PROBE"); env && *env) return {fs::path(env)};
  Dl_info info{};
  if (!dladdr(reinterpret_cast<void*>(&readVdb), &info) || !info.dli_fname) return {};
  const fs::path folder = fs::path(info.dli_fname).parent_path();
  return {folder / "millsim-vdb-probe", (folder / MILLSIM_VDB_PROBE_FROM_LIBDIR / "millsim-vdb-probe").lexically_normal()};
}

void readInAProbeFirst(const std::string& name) {
  const std::vector<fs::path> candidates = probeCandidates();
  fs::path probe;
  std::string tried;
  for (const fs::path& c : candidates) {
    if (access(c.c_str(), X_OK) == 0) {
      probe = c;
      break;
    }
    tried += (tried.empty() ? "" : ", ") + c.string();
  }
  if (probe.empty())
    throw VolumeError(name + ": cannot check the file: MillSim's OpenVDB reader millsim-vdb-probe is not at " +
                      (tried.empty() ? std::string("any known place") : tried) +
                      " (reinstall MillSim, or set MILLSIM_VDB_PROBE to its path)");
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) throw VolumeError(name + ": cannot check the file (pipe: " + std::strerror(errno) + ")");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[1], STDOUT_FILENO);  // dup2 clears close-on-exec
  const std::string probePath = probe.string();
  char* const argv[] = {const_cast<char*>(probePath.c_str()), const_cast<char*>(name.c_str()), nullptr};
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, probePath.c_str(), &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  close(fds[1]);
  if (spawned != 0) {
    close(fds[0]);
    throw VolumeError(name + ": cannot check the file (starting " + probePath + ": " + std::strerror(spawned) + ")");
  }
  // Wall-clock time too: the probe's CPU-time limit does not stop a process that waits.
  const int seconds = vdbReadSeconds(name);
  std::string message;
  char buffer[4096];
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
  bool late = false;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    pollfd p{fds[0], POLLIN, 0};
    const int ready = left.count() > 0 ? poll(&p, 1, int(std::min<long long>(left.count(), 1 << 30))) : 0;
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) {  // the deadline (the loop below kills the probe), or an error polling
      late = ready == 0;
      if (late) kill(pid, SIGKILL);
      break;
    }
    const ssize_t n = read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    if (message.size() < 65536) message.append(buffer, std::size_t(n));
  }
  close(fds[0]);
  // The probe's end, within the same deadline however the pipe ended (EOF, an
  // error, or the deadline itself); past it the probe is killed.
  int status = 0;
  for (;;) {
    const pid_t done = waitpid(pid, &status, late ? 0 : WNOHANG);
    if (done == pid) break;
    if (done < 0 && errno == EINTR) continue;
    if (done < 0)  // reaped elsewhere (SIGCHLD ignored, another thread's handler): nothing says the read succeeded
      throw VolumeError(name + ": cannot check the file (waitpid: " + std::strerror(errno) + ")");
    if (std::chrono::steady_clock::now() >= deadline) {
      kill(pid, SIGKILL);
      late = true;
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return;
  if (WIFEXITED(status) && WEXITSTATUS(status) == 1 && !message.empty()) throw VolumeError(message);
  // 126 and 127: the probe could not be started (not executable, or its libraries not found).
  if (WIFEXITED(status) && (WEXITSTATUS(status) == 126 || WEXITSTATUS(status) == 127))
    throw VolumeError(name + ": cannot check the file: " + probePath + " could not start (status " +
                      std::to_string(WEXITSTATUS(status)) + "; are its libraries, OpenVDB's, installed?)");
  const int signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  const std::string what =
      late                ? "did not finish within " + std::to_string(seconds) + " s"
      : signal == SIGXCPU ? "used more than " + std::to_string(seconds) + " s of CPU time"
      : signal != 0       ? "crashed on it (signal " + std::to_string(signal) + ", " + strsignal(signal) + ")"
                          : "stopped with status " + std::to_string(WEXITSTATUS(status));
  throw VolumeError(name + ": corrupt OpenVDB file: OpenVDB's reader " + what +
                    " (it was read in a separate process first, " + probePath + ")");
}

}  // namespace

VoxelVolume readVdb(const fs::path& file, float airValue) {
  const std::string name = file.string();
  requireFile(file, "a .vdb file");
  checkVdbStructure(file, name);  // before OpenVDB trusts the file's counts and lengths
  openvdb::initialize();

  readInAProbeFirst(name);
  const openvdb::GridPtrVecPtr grids = readVdbGrids(name);

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
