#include "SweepProcesses.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>

extern char** environ;

namespace millsim::app {
namespace fs = std::filesystem;

namespace {

struct SpawnSetup {
  posix_spawn_file_actions_t actions;
  posix_spawnattr_t attr;
  SpawnSetup() {
    posix_spawn_file_actions_init(&actions);
    posix_spawnattr_init(&attr);
    // The child starts with default handlers and nothing blocked, whatever
    // the sweep has set up for itself.
    sigset_t none, defaults;
    sigemptyset(&none);
    sigemptyset(&defaults);
    for (int s : {SIGINT, SIGTERM, SIGPIPE, SIGHUP}) sigaddset(&defaults, s);
    posix_spawnattr_setsigmask(&attr, &none);
    posix_spawnattr_setsigdefault(&attr, &defaults);
  }
  ~SpawnSetup() {
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attr);
  }
};

std::vector<char*> argvOf(std::vector<std::string>& args) {
  std::vector<char*> v;
  for (std::string& a : args) v.push_back(a.data());
  v.push_back(nullptr);
  return v;
}

}  // namespace

fs::path millsimExecutable() { return fs::read_symlink("/proc/self/exe"); }

pid_t startCell(const fs::path& exe, const sweep::Cell& cell, const fs::path& folder, bool ownGroup) {
  std::error_code ec;
  fs::remove_all(folder, ec);
  fs::create_directories(folder);
  {
    std::ofstream command(folder / "command.txt");
    command << sweep::shellQuoted(cell.args) << "\n";
  }
  SpawnSetup s;
  const std::string out = (folder / "stdout.txt").string(), err = (folder / "stderr.txt").string();
  posix_spawn_file_actions_addopen(&s.actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&s.actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&s.actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addchdir_np(&s.actions, folder.c_str());
  posix_spawnattr_setpgroup(&s.attr, 0);
  posix_spawnattr_setflags(&s.attr, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF | (ownGroup ? POSIX_SPAWN_SETPGROUP : 0));
  std::vector<std::string> args{exe.string()};
  args.insert(args.end(), cell.args.begin(), cell.args.end());
  std::vector<char*> argv = argvOf(args);
  pid_t pid = 0;
  if (const int e = posix_spawn(&pid, exe.c_str(), &s.actions, &s.attr, argv.data(), environ); e != 0)
    throw std::runtime_error("cannot start " + exe.string() + ": " + std::strerror(e));
  return pid;
}

FolderLock::FolderLock(const fs::path& out) {
  fs::create_directories(out);
  fd_ = ::open((out / ".lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0 || ::flock(fd_, LOCK_EX | LOCK_NB) != 0)
    throw std::runtime_error(out.string() + " is in use by another `millsim sweep` (running or submitting its cells); "
                             "wait for it, or give this one another --out");
}

FolderLock::~FolderLock() {
  if (fd_ >= 0) ::close(fd_);
}

int exitCodeOf(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 1;
}

Captured capture(const std::vector<std::string>& command) {
  Captured c;
  int outPipe[2], errPipe[2];
  if (pipe2(outPipe, O_CLOEXEC) != 0) return c;
  if (pipe2(errPipe, O_CLOEXEC) != 0) {
    close(outPipe[0]), close(outPipe[1]);
    return c;
  }
  SpawnSetup s;
  posix_spawn_file_actions_addopen(&s.actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&s.actions, outPipe[1], 1);
  posix_spawn_file_actions_adddup2(&s.actions, errPipe[1], 2);
  posix_spawnattr_setflags(&s.attr, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  std::vector<std::string> args = command;
  std::vector<char*> argv = argvOf(args);
  pid_t pid = 0;
  const int e = posix_spawnp(&pid, args[0].c_str(), &s.actions, &s.attr, argv.data(), environ);
  close(outPipe[1]), close(errPipe[1]);
  if (e == 0) {
    pollfd fds[2] = {{outPipe[0], POLLIN, 0}, {errPipe[0], POLLIN, 0}};
    std::string* into[2] = {&c.out, &c.err};
    int open = 2;
    while (open > 0) {
      if (poll(fds, 2, -1) < 0) {
        if (errno == EINTR) continue;
        break;
      }
      for (int i = 0; i < 2; ++i) {
        if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
        char buf[4096];
        const ssize_t n = read(fds[i].fd, buf, sizeof buf);
        if (n > 0) {
          into[i]->append(buf, std::size_t(n));
        } else if (n == 0 || errno != EINTR) {
          fds[i].fd = -1;
          --open;
        }
      }
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    c.exitCode = exitCodeOf(status);
  }
  close(outPipe[0]), close(errPipe[0]);
  return c;
}

}  // namespace millsim::app
