// An LD_PRELOAD shim for the `device` tests of the 3D mouse: the real libspnav
// connects to spacenavd at a fixed path (/var/run/spnav.sock), which only root
// may create. With MILLSIM_SPNAV_SOCKET set, this library's connect() sends
// that one address to the given socket instead, where MillSim's fake spacenavd
// (FakeSpacenavd.cpp) listens, so the tests run the real library without root
// and touch nothing under /var/run. With MILLSIM_SPNAV_SOCKET set it never
// falls through to the real daemon's socket: no fake daemon, no connection.
// Every other connect() passes through unchanged. Built only with the tests,
// never installed.
#include <dlfcn.h>
#include <errno.h>
#include <sys/socket.h>
#include <sys/un.h>

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <cstring>

namespace {

using ConnectFn = int (*)(int, const sockaddr*, socklen_t);

ConnectFn realConnect() {
  static ConnectFn real = reinterpret_cast<ConnectFn>(dlsym(RTLD_NEXT, "connect"));
  return real;
}

// Whether addr is spacenavd's AF_UNIX socket (either spelling of the run directory).
bool isSpacenavd(const sockaddr* addr, socklen_t len) {
  constexpr std::size_t kPathAt = offsetof(sockaddr_un, sun_path);
  if (!addr || len <= kPathAt || addr->sa_family != AF_UNIX) return false;
  const auto* un = reinterpret_cast<const sockaddr_un*>(addr);
  const std::size_t max = std::min<std::size_t>(len - kPathAt, sizeof un->sun_path);
  const std::size_t n = strnlen(un->sun_path, max);
  const auto is = [&](const char* p) { return n == std::strlen(p) && std::memcmp(un->sun_path, p, n) == 0; };
  return is("/var/run/spnav.sock") || is("/run/spnav.sock");
}

}  // namespace

extern "C" int connect(int fd, const sockaddr* addr, socklen_t len) {
  ConnectFn real = realConnect();
  if (!real) {
    errno = ENOSYS;
    return -1;
  }
  const char* to = std::getenv("MILLSIM_SPNAV_SOCKET");
  if (!to || !*to || !isSpacenavd(addr, len)) return real(fd, addr, len);
  sockaddr_un redirected{};
  redirected.sun_family = AF_UNIX;
  if (std::strlen(to) >= sizeof redirected.sun_path) {
    errno = ENAMETOOLONG;
    return -1;
  }
  std::strcpy(redirected.sun_path, to);
  return real(fd, reinterpret_cast<const sockaddr*>(&redirected), sizeof redirected);
}
