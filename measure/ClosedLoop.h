#pragma once
// The closed-loop harness: a renderer, a VoxelScene and the simulated hand
// (HandDevice's driver) run through HapticLoop::stepSimulated at 1 kHz, so the
// safety layer, the zero-order hold and the one-frame delay are the real ones.
// Optionally drops a fraction of device samples (the loop then holds the last
// pose, as with a real device that misses a frame) and stalls the loop.
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "millsim/devices/HandDevice.h"
#include "millsim/devices/Trajectory.h"
#include "millsim/run/HapticLoop.h"

namespace millsim::measure {

struct HandRun {
  HandRun(Trajectory ref, const HandModel& grip) : reference(std::move(ref)), hand(grip) {}
  Trajectory reference;
  HandModel hand;
  double seconds = 2.0;
  double rate = 1000.0;
  double dropFraction = 0.0;  // device samples marked invalid, at random
  std::uint64_t seed = 1;
  // The loop stalls (host preemption): frame round(at·rate) comes `length`
  // seconds after the one before it instead of one period.
  struct Stall {
    double at = 0.0, length = 0.0;  // s
  };
  std::vector<Stall> stalls;
};

struct TraceFrame {
  double t = 0.0;
  Pose device;        // the true device pose this frame (not the held one)
  glm::dvec3 force{0.0}, torque{0.0};  // sent to the device (after the safety layer)
  HapticOutput out;   // the renderer's output
  double energy = 0.0;     // passivity observer E(n), J (see passivityEnergy)
  double energyZoh = 0.0;  // the exact work of the held wrench (see passivityEnergy)
};

struct Trace {
  std::vector<TraceFrame> frames;
  double dt = 1e-3;
  long suppressed = 0;  // frames whose output the renderer or loop had to zero
};

Trace runClosedLoop(VoxelScene& scene, std::unique_ptr<HapticAlgorithm> algorithm, const HandRun& run);

// The passivity observer (Hannaford & Ryu 2002) at the device port, with
// v(k) = (x(k) − x(k−1))/T and ω(k) = Δθ(k)/T from the device pose differences
// (Δθ the rotation vector of q(k)·q(k−1)⁻¹):
//   E(n)    = −T·Σ_{k=1..n} [F(k)·v(k) + τ(k)·ω(k)]        (the observer as specified)
//   Ezoh(n) = −T·Σ_{k=1..n} [F(k−1)·v(k) + τ(k−1)·ω(k)]    (the exact work of the wrench
//             held by the zero-order hold over the interval in which the device moved)
// F, τ: the wrench sent to the hand. The sign makes E the energy the virtual
// environment has absorbed: a passive environment keeps E ≥ 0; E < 0 means it
// has put energy into the hand. Ezoh includes the one-frame hold, which makes
// any sampled spring active by about K·T/2 per unit of v² (Colgate & Brown);
// E does not. Fills both into the trace and returns min E.
double passivityEnergy(Trace& trace);

// Largest peak-to-peak excursion of the device position over frames [a, b), any axis (m).
double peakToPeak(const Trace& trace, std::size_t a, std::size_t b);
// Largest device speed over frames [a, b) (m/s), from position differences.
double peakSpeed(const Trace& trace, std::size_t a, std::size_t b);
// True if every force, torque and drawn pose in the trace is finite.
bool allFinite(const Trace& trace);

// Rotation vector (axis·angle, |angle| ≤ π) of a unit quaternion.
glm::dvec3 rotationVector(glm::dquat q);

}  // namespace millsim::measure
