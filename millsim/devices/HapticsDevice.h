#pragma once
// HapticsDevice: the base of device nodes (AresDevice, HandDevice,
// TrajectoryDevice). Field names follow H3DAPI's H3DHapticsDevice where they
// apply. The device holds the tool and the haptics renderer; swapping the
// renderer element switches the algorithm.
#include <memory>
#include <optional>
#include <string>

#include "millsim/core/NodeKinds.h"
#include "millsim/devices/PositionCalibration.h"
#include "millsim/devices/Trajectory.h"
#include "millsim/driver/DeviceDriver.h"
#include "millsim/haptics/HapticsRenderer.h"
#include "millsim/haptics/MillTool.h"

namespace millsim {

class PointerInput;

struct DriverOptions {
  // Simulated devices: follow this trajectory instead of the one in the
  // scene (millsim replay --trajectory). Hardware ignores it.
  const Trajectory* trajectory = nullptr;
  // MouseDevice: the window's mouse (millsim/devices/MouseDevice.h).
  PointerInput* pointer = nullptr;
};

class HapticsDevice : public ChildNode {
public:
  SFVec3f devicePosition{this, "devicePosition", Access::OutputOnly, glm::vec3(0.f),
                         "Burr centre position, calibrated, world frame (m)."};
  SFRotation deviceOrientation{this, "deviceOrientation", Access::OutputOnly, Rotation{},
                               "Tool orientation, calibrated, world frame."};
  SFVec3f force{this, "force", Access::OutputOnly, glm::vec3(0.f), "Force last sent to the device (N)."};
  SFVec3f torque{this, "torque", Access::OutputOnly, glm::vec3(0.f),
                 "Torque last sent to the device, about the burr centre (N·m)."};
  SFBool mainButton{this, "mainButton", Access::OutputOnly, false, "Milling switch: true while the burr spins."};
  SFBool inContact{this, "inContact", Access::OutputOnly, false,
                   "True while the renderer reports contact (colliding vertices or shell points)."};
  SFFloat contactForce{this, "contactForce", Access::OutputOnly, 0.f,
                       "Magnitude of the force last sent to the device (N)."};
  SFVec3f proxyPosition{this, "proxyPosition", Access::OutputOnly, glm::vec3(0.f),
                        "Burr centre of the tool as the renderer draws it (its proxy or coupled tool), world frame (m)."};
  SFRotation proxyOrientation{this, "proxyOrientation", Access::OutputOnly, Rotation{},
                              "Orientation of the tool as the renderer draws it, world frame."};
  SFFloat hapticsRate{this, "hapticsRate", Access::OutputOnly, 0.f, "Measured haptic loop rate (Hz)."};
  SFTime hapticsLoopTime{this, "hapticsLoopTime", Access::OutputOnly, Time{},
                         "Compute time of the last haptic frame (s)."};
  SFInt32 desiredHapticsRate{this, "desiredHapticsRate", Access::InitializeOnly, 1000,
                             "Haptic loop rate to run at (Hz).", Range::closed(1, 20000)};
  SFFloat forceLimit{this, "forceLimit", Access::InputOutput, 10.f, "Largest force sent to the device (N); live: a change applies from the next frame.",
                     Range::openClosed(0, 50).in(quantity::force).usually(1, 50)};
  SFFloat torqueLimit{this, "torqueLimit", Access::InputOutput, 0.5f, "Largest torque sent to the device (N·m); live.",
                      Range::openClosed(0, 5).in(quantity::torque).usually(0.02, 5)};
  SFFloat positionScale{this, "positionScale", Access::InputOutput, 1.f,
                        "Scene metres per device metre: scene position = positionScale · (orientationCalibration · "
                        "raw) + positionCalibration. The device gets positionScale × the rendered force (energy "
                        "conserved), so a scene stiffness k is felt as positionScale² · k. Read when a run starts; "
                        "H3DAPI's 4x4 positionCalibration with a uniform scale sets it.",
                        Range::closed(0.001, 1000)};
  PositionCalibration positionCalibration{
      this, "positionCalibration", Access::InputOutput, glm::vec3(0.f),
      "Offset added to the scaled device position (m). H3DAPI's 4x4 matrix form is read when it translates and "
      "scales uniformly (the scale goes to positionScale).",
      Range::closed(-10, 10).in(quantity::length)};
  SFRotation orientationCalibration{this, "orientationCalibration", Access::InputOutput, Rotation{},
                                    "Rotation applied to raw device poses (about the world origin)."};
  SFBool enabled{this, "enabled", Access::InputOutput, true, "When false, no force or torque is sent; live."};
  SFNodeOf<MillTool> tool{this, "tool", Access::InputOutput, "The milling tool the device holds."};
  SFNodeOf<HapticsRendererNode> hapticsRenderer{this, "hapticsRenderer", Access::InputOutput,
                                                "The algorithm that computes force and torque; live in the window of millsim run (keys 1-3, or a new node of a prepared type)."};
  // H3DAPI's stylus field, so that an H3DAPI scene's <Group containerField="stylus"> loads.
  SFNodeOf<ChildNode> stylus{this, "stylus", Access::InputOutput,
                             "H3DAPI's stylus: what H3D draws at the device's pose. Accepted so that an H3DAPI scene "
                             "loads, but not drawn: MillSim draws the MillTool's burr and shaft there (a warning says "
                             "so)."};
  bool showsField(const Field& f) const override { return &f != &stylus; }

  HapticsDevice() { positionCalibration.scaleInto(positionScale); }

  // Raw device pose → calibrated world pose.
  Pose calibrate(const Pose& raw) const;

  // Opens the haptic thread's side of this device for one run (scene thread).
  // Throws DeviceError with a message for the user (what was looked for,
  // what was found) when the device cannot be opened.
  virtual std::unique_ptr<DeviceDriver> openDriver(const DriverOptions& options) const = 0;
  // True for simulated devices that follow a trajectory (TrajectoryDevice,
  // HandDevice): replay hands them its trajectory. A replay of a hardware
  // device plays the trajectory open loop instead.
  virtual bool followsTrajectory() const { return false; }
  // The trajectory a simulated device loaded from its url (null for hardware
  // or an empty url): what replay and render follow by default.
  virtual std::shared_ptr<const Trajectory> trajectory() const { return nullptr; }
  // How long (s) the device keeps applying the last wrench when no new one
  // arrives. The safety layer blends a late frame within it from that wrench;
  // after it the device has dropped the wrench, and so does the layer
  // (SafetyLimits::deviceHold). 0 (the default): unknown, every late frame
  // is zeroed.
  virtual double outputHoldTime() const { return 0.0; }

  // A device the window's pointer moves (MouseDevice, and AnyDevice, which
  // falls back on it): where the tool starts and how far one Ctrl+wheel
  // notch moves it. Nothing for a device a hand or a trajectory moves.
  struct PointerStart {
    Pose pose;
    double depthStep = 2e-4;  // m
  };
  virtual std::optional<PointerStart> pointerStart() const { return std::nullopt; }
  // After openDriver (scene thread): whether what was opened follows the
  // window's pointer (AnyDevice: only when it found nothing else).
  virtual bool followsPointer() const { return pointerStart().has_value(); }
  // After openDriver (scene thread): what was opened, for the user, and in
  // the node's own output fields; empty when the node's type says it all.
  virtual std::string noteOpened() { return {}; }
  // `millsim check`: a hardware device asks its library whether it could be
  // opened now. Nothing for simulated devices (they always open).
  virtual std::optional<DeviceProbe> probe() const { return std::nullopt; }
  void initialize(DiagnosticSink& sink) override;
};

}  // namespace millsim
