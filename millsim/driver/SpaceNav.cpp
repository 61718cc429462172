#include "millsim/driver/SpaceNav.h"

#include <poll.h>
#include <sys/socket.h>

#include <algorithm>
#include <cmath>
#include <mutex>

#include "millsim/driver/DeviceDriver.h"

// Last: libspnav's header brings X11's, whose macros (Success, None, Bool)
// would break any header after it; this file is built on its own, outside
// the unity build, for the same reason (millsim/CMakeLists.txt).
#include <spnav.h>

namespace millsim {

namespace {
std::mutex gOpenMutex;  // open() on the scene thread only; guards the weak pointer
std::weak_ptr<SpaceNav> gShared;
}  // namespace

SpaceNavDeflection toSceneFrame(const SpaceNavState& s, double deadZone) {
  const auto frac = [deadZone](int v) {
    const double f = std::clamp(double(v) / SpaceNav::kFullScale, -1.0, 1.0);
    return std::abs(f) < deadZone ? 0.0 : f;
  };
  return {{frac(s.axes[0]), frac(s.axes[1]), -frac(s.axes[2])}, {frac(s.axes[3]), frac(s.axes[4]), -frac(s.axes[5])}};
}

std::shared_ptr<SpaceNav> SpaceNav::open() {
  std::lock_guard lock(gOpenMutex);
  if (auto shared = gShared.lock(); shared && shared->connected()) return shared;
  if (spnav_open() == -1)
    throw DeviceError(
        "could not connect to the spacenavd daemon (/var/run/spnav.sock): install it (Debian package spacenavd) "
        "and start it (sudo systemctl start spacenavd), with the 3D mouse plugged in");
  std::shared_ptr<SpaceNav> shared(new SpaceNav);
  gShared = shared;
  return shared;
}

SpaceNav::SpaceNav() {
  char name[128] = {};
  // libspnav 1.0 asks the daemon (protocol 1); an older daemon does not say.
  if (spnav_protocol() >= 1 && spnav_dev_name(name, sizeof name) > 0) deviceName_ = name;
  reader_ = std::thread([this] { run(); });
}

SpaceNav::~SpaceNav() {
  stop_.store(true, std::memory_order_release);
  if (reader_.joinable()) reader_.join();
  spnav_close();
}

void SpaceNav::publish(const SpaceNavState& s) {
  sequence_.fetch_add(1, std::memory_order_acq_rel);  // odd: writing
  for (int i = 0; i < 6; ++i) axes_[std::size_t(i)].store(s.axes[std::size_t(i)], std::memory_order_relaxed);
  buttons_.store(s.buttons, std::memory_order_relaxed);
  latestPress_.store(s.latestPress, std::memory_order_relaxed);
  latestRelease_.store(s.latestRelease, std::memory_order_relaxed);
  events_.store(s.events, std::memory_order_relaxed);
  sequence_.fetch_add(1, std::memory_order_release);  // even: done
}

SpaceNavState SpaceNav::state() const {
  SpaceNavState s;
  for (;;) {
    const std::uint32_t before = sequence_.load(std::memory_order_acquire);
    if (before & 1u) continue;  // a write is under way: a few stores long
    for (int i = 0; i < 6; ++i) s.axes[std::size_t(i)] = axes_[std::size_t(i)].load(std::memory_order_relaxed);
    s.buttons = buttons_.load(std::memory_order_relaxed);
    s.latestPress = latestPress_.load(std::memory_order_relaxed);
    s.latestRelease = latestRelease_.load(std::memory_order_relaxed);
    s.events = events_.load(std::memory_order_relaxed);
    std::atomic_thread_fence(std::memory_order_acquire);
    if (sequence_.load(std::memory_order_relaxed) == before) return s;
  }
}

void SpaceNav::run() {
  SpaceNavState s;
  pollfd p{spnav_fd(), POLLIN, 0};
  while (!stop_.load(std::memory_order_acquire)) {
    // Wake at least every 20 ms to see stop_; the daemon's events wake it at once.
    const int ready = poll(&p, 1, 20);
    if (ready < 0) continue;  // EINTR
    if (ready > 0 && (p.revents & (POLLHUP | POLLERR | POLLNVAL)) && !(p.revents & POLLIN)) {
      failure_ = "spacenavd closed the connection to the 3D mouse (the daemon stopped?)";
      connected_.store(false, std::memory_order_release);
      return;
    }
    if (ready == 0) continue;
    bool changed = false;
    spnav_event e;
    int type;
    while ((type = spnav_poll_event(&e)) != 0) {
      changed = true;
      ++s.events;
      if (type == SPNAV_EVENT_MOTION) {
        s.axes = {e.motion.x, e.motion.y, e.motion.z, e.motion.rx, e.motion.ry, e.motion.rz};
      } else if (type == SPNAV_EVENT_BUTTON && e.button.bnum >= 0 && e.button.bnum < 32) {
        const unsigned bit = 1u << unsigned(e.button.bnum);
        if (e.button.press) s.buttons |= bit, s.latestPress = e.button.bnum;
        else s.buttons &= ~bit, s.latestRelease = e.button.bnum;
      }
    }
    if (changed) {
      publish(s);
      continue;
    }
    // Readable but no event: a reply or part of one, or the daemon hung up (end of stream).
    char byte;
    if (recv(p.fd, &byte, 1, MSG_PEEK | MSG_DONTWAIT) == 0) {
      failure_ = "spacenavd closed the connection to the 3D mouse (the daemon stopped?)";
      connected_.store(false, std::memory_order_release);
      return;
    }
  }
}

}  // namespace millsim
