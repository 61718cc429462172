// millsim-vdb-probe FILE: reads a .vdb file whole with OpenVDB, in a process
// of its own, before readVdb reads it in the caller's (VdbFile.cpp says why).
// Exit 0: read whole. Exit 1: OpenVDB or the size checks refused it, and the
// reason is on stdout. Killed by its limits or crashed: a corrupt file.
//
// A fresh process, not a fork: a forked copy of a process with other threads
// (TBB's workers, a haptic loop) inherits every lock those threads held at the
// fork, and CI saw one such child wait a whole minute.
#include <unistd.h>

#include <sys/resource.h>

#include <cstdio>
#include <string>

#include "millsim/volume/VdbGrids.h"

namespace {

// CPU time as the caller's wall-clock limit (vdbReadSeconds); the address
// space is what this process maps now (under ASan, its shadow) plus what a
// volume's grid may take (millsim::kMaxGridBytes) and a margin.
void limitThisProcess(const char* file) {
  // The soft limit sends SIGXCPU (what the caller reports); the hard one, 2 s
  // later, SIGKILL. No core file for a corrupt file's crash.
  rlimit cpu{};
  cpu.rlim_cur = rlim_t(millsim::vdbReadSeconds(file));
  cpu.rlim_max = cpu.rlim_cur + 2;
  setrlimit(RLIMIT_CPU, &cpu);
  rlimit core{};
  setrlimit(RLIMIT_CORE, &core);
  long pages = 0;
  if (std::FILE* statm = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(statm, "%ld", &pages) != 1) pages = 0;
    std::fclose(statm);
  }
  if (pages > 0) {  // without /proc the current size is unknown: no limit rather than a wrong one
    rlimit as{};
    as.rlim_cur = as.rlim_max =
        rlim_t(pages) * rlim_t(sysconf(_SC_PAGESIZE)) + rlim_t(millsim::kMaxGridBytes) + (rlim_t(1) << 30);
    setrlimit(RLIMIT_AS, &as);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: millsim-vdb-probe FILE.vdb (MillSim's volume reader runs it)\n");
    return 2;
  }
  limitThisProcess(argv[1]);
  std::string message;
  try {
    openvdb::initialize();
    millsim::readVdbGrids(argv[1]);
    return 0;
  } catch (const std::exception& e) {
    message = e.what();
  } catch (...) {
    message = std::string(argv[1]) + ": cannot read as an OpenVDB file";
  }
  std::fwrite(message.data(), 1, message.size(), stdout);
  std::fflush(stdout);
  return 1;
}
