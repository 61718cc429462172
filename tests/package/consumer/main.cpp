// Loads a scene through the installed MillSim library and counts its nodes.
#include <iostream>

#include <millsim/core/NodeRegistry.h>
#include <millsim/x3d/X3DLoader.h>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  millsim::LoadResult r = millsim::loadSceneFile(argv[1], millsim::builtinRegistry());
  std::cerr << r.report();
  if (!r.ok()) return 2;
  std::cout << "nodes: " << r.scene->nodeCount() << "\n";
  return 0;
}
