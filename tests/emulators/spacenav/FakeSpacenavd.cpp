// A fake spacenavd for the `device` tests of the 3D mouse: the real libspnav
// (redirected here by SocketRedirect.cpp) talks to it as to the daemon, and it
// plays a script of the puck's motion and buttons. Built only with the tests.
//
//   fake-spacenavd SOCKET_PATH SCRIPT.csv
//
// It listens on SOCKET_PATH, accepts one client (then stops listening), and
// speaks spacenavd 1.0's AF_UNIX protocol: the client's 4-byte protocol request
// (answered: version 1), then 32-byte requests (client name, sensitivity,
// event mask, device name, axes, buttons, USB id, type: a "SpaceNavigator
// (MillSim's fake spacenavd)", 6 axes, 2 buttons) and 32-byte events.
// SCRIPT.csv: `t,kind,a,b,c,d,e,f`, t in seconds since the client connected,
// kind `motion` (x y z rx ry rz), `button` (number, 1 press / 0 release) or
// `exit` (close the connection and exit); '#' lines are comments. Events wait
// for the client's start-up requests (the protocol answered, then 20 ms without
// a request; 0.5 s at most): libspnav takes an event that comes while it waits
// for an answer as a wrong answer, and drops those pending when it asks. After
// the script it exits when the client hangs up, or 60 s after the last event.
// Errors: stderr, exit 1.
#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;
using Word = std::int32_t;

// The protocol's numbers (libspnav 1.0 src/proto.h; spacenavd 1.0 src/proto.h).
// A request or an answer is 8 words: its type, then data[0..6]; data[6] (word 7)
// is the status, or what remains of a string.
constexpr Word kReqTag = 0x7faa0000, kChangeProto = 0x5500, kMaxProto = 1;
enum : Word { kUevMotion = 0, kUevPress = 1, kUevRelease = 2 };
enum : Word { kSetName = 0x1000, kSetSens, kGetSens, kSetEvmask, kGetEvmask };
enum : Word { kDevName = 0x2000, kDevPath, kDevAxes, kDevButtons, kDevUsbId, kDevType };
constexpr Word kMaskMotion = 1, kMaskButton = 2, kMaskDev = 4;
constexpr Word kSpaceNavigator = 0x206;  // DEV_SNAV
constexpr double kStartUp = 0.5, kSettle = 0.02, kLinger = 60.0;

struct Step {
  double t;
  std::string kind;  // motion | button | exit
  Word v[6];
};

std::vector<Step> loadScript(const char* path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(std::string(path) + ": cannot read the script");
  std::vector<Step> steps;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    const auto fail = [&](const std::string& why) {
      throw std::runtime_error(std::string(path) + ":" + std::to_string(n) + ": " + why + ": '" + line + "'");
    };
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    std::vector<std::string> f;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) {
      const std::size_t a = cell.find_first_not_of(" \t"), b = cell.find_last_not_of(" \t");
      f.push_back(a == std::string::npos ? "" : cell.substr(a, b - a + 1));
    }
    Step s{0.0, f.size() > 1 ? f[1] : "", {}};
    char* end = nullptr;
    s.t = std::strtod(f[0].c_str(), &end);
    if (f[0].empty() || *end || !(s.t >= 0.0 && s.t < 1e6)) fail("the time is not seconds >= 0");
    if (!steps.empty() && s.t < steps.back().t) fail("the times go backwards");
    const std::size_t want = s.kind == "motion" ? 6 : s.kind == "button" ? 2 : 0;
    if (want == 0 && s.kind != "exit") fail("the kind is not motion, button or exit");
    if (f.size() != 2 + want) fail(s.kind + " takes " + std::to_string(want) + " values");
    for (std::size_t i = 0; i < want; ++i) {
      const long v = std::strtol(f[2 + i].c_str(), &end, 10);
      if (f[2 + i].empty() || *end || v < INT32_MIN || v > INT32_MAX)
        fail("value " + std::to_string(i + 1) + " is not an integer");
      s.v[i] = Word(v);
    }
    if (s.kind == "button" && (s.v[0] < 0 || (s.v[1] != 0 && s.v[1] != 1))) fail("a button is 'number,1|0'");
    steps.push_back(s);
  }
  return steps;
}

struct Client {
  int fd = -1;
  Word proto = 0;                           // 0 until the client asks for more
  Word evmask = kMaskMotion | kMaskButton;  // protocol 0's
  float sensitivity = 1.0f;
  bool answered = false;   // the protocol request
  double lastRequest = 0;  // s since connected
  std::string in;          // bytes of a message not yet whole

  bool send(const void* data, std::size_t size) const {
    for (auto* p = static_cast<const char*>(data); size > 0;) {
      const ssize_t n = ::send(fd, p, size, MSG_NOSIGNAL);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return false;
      p += n, size -= std::size_t(n);
    }
    return true;
  }
  bool reply(Word* r, Word status) const {
    r[7] = status;
    return send(r, 32);
  }
  bool sendString(Word type, const std::string& s) const {  // 24 bytes an answer, data[6] what remains
    for (std::size_t at = 0; at == 0 || at < s.size(); at += 24) {
      Word r[8] = {type, 0, 0, 0, 0, 0, 0, Word(s.size() - at) | (at ? 0x10000 : 0)};
      std::memcpy(r + 1, s.data() + at, std::min<std::size_t>(24, s.size() - at));
      if (!send(r, 32)) return false;
    }
    return true;
  }
  bool request(Word* r) {  // a protocol-1 request, answered as spacenavd 1.0 does
    float f;
    switch (r[0] & 0xffff) {
      case kSetName: return true;  // not answered; the name is not kept
      case kSetSens:
        std::memcpy(&f, r + 1, 4);
        if (!std::isfinite(f)) return reply(r, -1);
        sensitivity = f;
        return reply(r, 0);
      case kGetSens: std::memcpy(r + 1, &sensitivity, 4); return reply(r, 0);
      case kSetEvmask: evmask = r[1]; return reply(r, 0);
      case kGetEvmask: r[1] = evmask; return reply(r, 0);
      case kDevName: return sendString(r[0], "SpaceNavigator (MillSim's fake spacenavd)");
      case kDevPath: return sendString(r[0], "/dev/input/millsim-fake-spacenav");
      case kDevAxes: r[1] = 6; return reply(r, 0);
      case kDevButtons: r[1] = 2; return reply(r, 0);
      case kDevUsbId: r[1] = 0x046d, r[2] = 0xc626; return reply(r, 0);
      case kDevType: r[1] = kSpaceNavigator; return reply(r, 0);
      default: return reply(r, -1);
    }
  }
  bool receive(double now) {  // false: the client hung up
    lastRequest = now;
    char buf[512];
    ssize_t n;
    while ((n = ::recv(fd, buf, sizeof buf, 0)) < 0 && errno == EINTR) {}
    if (n <= 0) return false;
    in.append(buf, std::size_t(n));
    for (std::size_t size; in.size() >= (size = proto == 0 ? 4 : 32); in.erase(0, size)) {
      Word r[8];
      std::memcpy(r, in.data(), size);
      if (proto == 0 && (r[0] & 0xffffff00) == (kReqTag | kChangeProto)) {  // protocol 0: 4-byte messages
        proto = std::min(r[0] & 0xff, kMaxProto);
        if (proto > 0) evmask = kMaskMotion | kMaskButton | kMaskDev;
        answered = true;
        const Word answer = kReqTag | kChangeProto | proto;
        if (!send(&answer, 4)) return false;
      } else if (proto == 0) {  // protocol 0's only other message: a sensitivity
        std::memcpy(&sensitivity, r, 4);
        if (!std::isfinite(sensitivity)) sensitivity = 1.0f;
      } else if (!request(r)) {
        return false;
      }
    }
    return true;
  }
};

[[noreturn]] void die(const std::string& message) {
  std::fprintf(stderr, "fake-spacenavd: %s\n", message.c_str());
  std::exit(1);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) die("usage: fake-spacenavd SOCKET_PATH SCRIPT.csv");
  std::vector<Step> steps;
  try {
    steps = loadScript(argv[2]);
  } catch (const std::exception& e) {
    die(e.what());
  }
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  if (std::strlen(argv[1]) >= sizeof addr.sun_path) die(std::string(argv[1]) + ": the socket path is too long");
  std::strcpy(addr.sun_path, argv[1]);
  ::unlink(argv[1]);  // a stale socket of an earlier run
  const int listener = socket(AF_UNIX, SOCK_STREAM, 0);
  if (listener < 0 || bind(listener, reinterpret_cast<sockaddr*>(&addr), sizeof addr) < 0 || listen(listener, 1) < 0)
    die(std::string(argv[1]) + ": " + std::strerror(errno));
  pollfd waiting{listener, POLLIN, 0};
  if (poll(&waiting, 1, int(kLinger * 1000)) != 1) die("no client connected in 60 s");
  Client c;
  if ((c.fd = ::accept(listener, nullptr, nullptr)) < 0) die(std::string("accept: ") + std::strerror(errno));
  const Clock::time_point start = Clock::now();
  ::close(listener);  // one client: another spnav_open() fails, as with no daemon
  ::unlink(argv[1]);

  const auto since = [start] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  double lastMotion = 0.0;
  const double end = (steps.empty() ? 0.0 : steps.back().t) + kLinger;
  for (std::size_t next = 0;;) {
    const double now = since();
    const bool held = now < kStartUp && (!c.answered || now < c.lastRequest + kSettle);
    if (next < steps.size() && steps[next].t <= now && !held) {
      const Step& s = steps[next++];
      Word e[8] = {};  // the event: its type, then 7 words
      if (s.kind == "exit") {
        ::close(c.fd);
        return 0;
      } else if (s.kind == "motion" && (c.evmask & kMaskMotion)) {
        e[0] = kUevMotion;
        for (int i = 0; i < 6; ++i) e[1 + i] = Word(float(s.v[i]) * c.sensitivity);  // as spacenavd scales
        e[7] = Word((now - lastMotion) * 1000.0);  // the period: ms since the last motion event
        lastMotion = now;
      } else if (s.kind == "button" && (c.evmask & kMaskButton)) {
        e[0] = s.v[1] ? kUevPress : kUevRelease, e[1] = s.v[0], e[2] = s.v[1];
      } else {
        continue;  // masked out by the client
      }
      if (!c.send(e, sizeof e)) return 0;  // the client hung up
      continue;
    }
    if (next == steps.size() && now >= end) return 0;
    double until = next < steps.size() ? steps[next].t : end;
    if (held) until = std::max(until, std::min(kStartUp, c.answered ? c.lastRequest + kSettle : kStartUp));
    pollfd p{c.fd, POLLIN, 0};
    const int ready = poll(&p, 1, std::max(0, int(std::ceil((until - now) * 1000.0))));
    if (ready < 0 && errno != EINTR) die(std::string("poll: ") + std::strerror(errno));
    if (ready > 0 && !c.receive(since())) return 0;  // the client hung up
  }
}
