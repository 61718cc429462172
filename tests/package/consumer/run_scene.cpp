// The smallest embedding of a run: load a scene, run its device for one
// simulated second through a Session, and print what it milled.
#include <exception>
#include <iostream>

#include <millsim/core/NodeRegistry.h>
#include <millsim/session/Session.h>
#include <millsim/x3d/X3DLoader.h>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: run_scene SCENE.x3d\n";
    return 2;
  }
  millsim::LoadResult loaded = millsim::loadSceneFile(argv[1], millsim::builtinRegistry());
  std::cerr << loaded.report();
  if (!loaded.ok()) return 2;
  try {
    auto session = millsim::Session::openDevice(*loaded.scene, millsim::SessionOptions{});
    const long frames = long(session->rate());  // one second of simulated time
    for (long n = 0; n < frames; ++n) session->stepSimulated();
    const millsim::SessionResult result = session->finish();
    std::cout << "frames: " << result.stats.frames << "\n"
              << "removed volume: " << result.stats.removedVolume * 1e9 << " mm3\n";
    return result.ok() ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "run_scene: error: " << e.what() << "\n";
    return 1;
  }
}
