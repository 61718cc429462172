// Algorithm #3's frames under the real workload, in thread CPU time: the
// device poses and button of a `millsim replay` log of the §8.2 procedure
// (x3d/default.x3d with a BarbicRenderer of pointShellScale s) are fed open
// loop to BarbicRenderer and VoxelScene::mill, exactly the calls the haptic
// loop makes, and each frame (step + stamp + shell update) is timed by the
// thread's CPU clock, so that a loaded host's preemption stays out of it.
// Since the renderer is deterministic, the frames are the replay's own.
// Frames are split as the log says: milling (button held, in contact),
// non-milling contact, free. Counters per class: p50 / p99 / max (µs); and
// the ratio of milling to non-milling contact p99.
//   MILLSIM_PROCEDURE_LOG=/tmp/replay-s%d.csv bench/procedure_bench
// (%d becomes the scale; make the logs with
//   millsim replay scene-s.x3d --trajectory x3d/trajectories/section-8-2.csv --log ...)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "millsim/run/ThreadCpuTime.h"
#include "millsim/renderers/BarbicRenderer.h"
#include "millsim/volume/ToothPhantom.h"
#include "millsim/volume/VoxelScene.h"

using namespace millsim;

namespace {

struct LoggedFrame {
  Pose device;
  bool button = false;
  int contacts = 0;
};

// The device pose (columns x..qz), contacts and button of every row.
std::vector<LoggedFrame> readLog(const std::string& path) {
  std::vector<LoggedFrame> frames;
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line)) return frames;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) f.push_back(cell);
    if (f.size() < 31) continue;
    LoggedFrame fr;
    fr.device.position = {std::stod(f[1]), std::stod(f[2]), std::stod(f[3])};
    fr.device.orientation = glm::dquat(std::stod(f[4]), std::stod(f[5]), std::stod(f[6]), std::stod(f[7]));
    fr.contacts = std::stoi(f[14]);
    fr.button = f[29] == "1";
    frames.push_back(fr);
  }
  return frames;
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, std::size_t(double(v.size()) * p))];
}

void BM_Procedure(benchmark::State& state) {
  const int scale = int(state.range(0));
  const char* pattern = std::getenv("MILLSIM_PROCEDURE_LOG");
  if (!pattern) {
    state.SkipWithError("set MILLSIM_PROCEDURE_LOG to a replay log (%d: the scale)");
    return;
  }
  char path[4096];
  std::snprintf(path, sizeof path, pattern, scale);
  const std::vector<LoggedFrame> frames = readLog(path);
  if (frames.empty()) {
    state.SkipWithError("no frames in the log");
    return;
  }
  const ToolGeometry tool{0.6e-3, 0.4e-3, 15e-3};  // x3d/default.x3d's MillTool
  std::vector<double> milling, contact, freeFrames;
  int mismatches = 0;
  for (auto _ : state) {
    VoxelVolume volume = makeToothPhantom(ToothPhantomOptions{});
    VoxelScene scene;
    scene.addVolume(volume, glm::dmat4(1.0), 700.0);
    BarbicRenderer renderer;
    renderer.pointShellScale.set(scale);
    auto algorithm = renderer.compile(tool, scene);
    algorithm->reset(frames.front().device);
    milling.clear(), contact.clear(), freeFrames.clear();
    milling.reserve(frames.size()), contact.reserve(frames.size()), freeFrames.reserve(frames.size());
    mismatches = 0;
    for (const LoggedFrame& f : frames) {
      const double c0 = threadCpuMicros();
      const HapticOutput out = algorithm->step(scene, HapticInput{f.device, 1e-3, f.button});
      if (f.button && out.burrCuts) scene.mill(out.burrCentre, tool.tipRadius);
      const double us = threadCpuMicros() - c0;
      mismatches += out.contacts != f.contacts;  // the log's own frames, or the comparison is off
      (f.button && out.contacts > 0 ? milling : out.contacts > 0 ? contact : freeFrames).push_back(us);
    }
  }
  state.counters["mill_p50"] = percentile(milling, 0.5);
  state.counters["mill_p99"] = percentile(milling, 0.99);
  state.counters["mill_max"] = percentile(milling, 1.0);
  state.counters["contact_p50"] = percentile(contact, 0.5);
  state.counters["contact_p99"] = percentile(contact, 0.99);
  state.counters["contact_max"] = percentile(contact, 1.0);
  state.counters["free_p99"] = percentile(freeFrames, 0.99);
  state.counters["mill_per_contact_p99"] = percentile(milling, 0.99) / std::max(1e-9, percentile(contact, 0.99));
  state.counters["milling_frames"] = double(milling.size());
  state.counters["mismatches"] = mismatches;
}
BENCHMARK(BM_Procedure)->ArgName("scale")->DenseRange(1, 3)->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace
