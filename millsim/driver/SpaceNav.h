#pragma once
// SpaceNav: a 3Dconnexion 3D mouse through the spacenavd daemon and its
// client library libspnav (Debian: spacenavd, libspnav-dev). libspnav keeps
// one connection per process, so this does too: the first open() connects
// and starts a reader thread that drains the daemon's events; every user
// (the SpaceMouseDevice's driver on the haptic thread, SpaceWareSensor on
// the scene thread) reads the newest state wait-free and never touches the
// socket. The connection closes when the last user lets it go.
#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>

namespace millsim {

// The puck and its buttons as the daemon last reported them.
struct SpaceNavState {
  // x, y, z, rx, ry, rz as spacenavd sends them (a SpaceNavigator reads
  // about ±350 at full deflection), in its frame: x right, y up, z away from
  // the user. In X3D's frame (z towards the user) that is (x, y, -z) and the
  // rotation (rx, ry, -rz), as libspnav's own spnav_posrot_moveobj turns
  // them for OpenGL: see toSceneFrame.
  std::array<int, 6> axes{};
  unsigned buttons = 0;            // bit i: button i is down
  int latestPress = -1;            // the last button pressed (-1: none yet)
  int latestRelease = -1;          // the last button released
  std::uint64_t events = 0;        // events received so far
};

// The deflection as fractions of full scale in X3D's frame: translation
// and rotation vectors, each component in [-1, 1], zero within `deadZone`.
struct SpaceNavDeflection {
  double translation[3];
  double rotation[3];
};
SpaceNavDeflection toSceneFrame(const SpaceNavState& s, double deadZone);

class SpaceNav {
public:
  // Full deflection in spacenavd's units (a SpaceNavigator's range).
  static constexpr double kFullScale = 350.0;

  // The process's connection, made on first use. Throws DeviceError saying
  // what to install or start when spacenavd cannot be reached.
  static std::shared_ptr<SpaceNav> open();
  ~SpaceNav();
  SpaceNav(const SpaceNav&) = delete;
  SpaceNav& operator=(const SpaceNav&) = delete;

  // The newest state; wait-free for the reader (it retries only while the
  // reader thread is writing a new one, a few stores long).
  SpaceNavState state() const;
  // False once the daemon closed the connection; failure() then says so
  // (written once before connected() turns false, so reading it after is safe).
  bool connected() const { return connected_.load(std::memory_order_acquire); }
  const std::string& failure() const { return failure_; }
  // What the daemon says the device is ("SpaceNavigator"), when it says.
  const std::string& deviceName() const { return deviceName_; }

private:
  SpaceNav();
  void run();
  void publish(const SpaceNavState& s);

  std::atomic<std::uint32_t> sequence_{0};  // odd while the reader thread writes
  std::array<std::atomic<int>, 6> axes_{};
  std::atomic<unsigned> buttons_{0};
  std::atomic<int> latestPress_{-1}, latestRelease_{-1};
  std::atomic<std::uint64_t> events_{0};
  std::atomic<bool> connected_{true}, stop_{false};
  std::string failure_, deviceName_;
  std::thread reader_;
};

}  // namespace millsim
