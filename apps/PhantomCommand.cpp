// millsim phantom --out FILE: writes the embedded tooth phantom to a volume file.
#include <chrono>
#include <iostream>

#include "Commands.h"
#include "millsim/volume/ToothPhantom.h"
#include "millsim/volume/VolumeIO.h"

namespace millsim::app {

void addPhantomCommand(CLI::App& app, int& result) {
  auto* cmd = app.add_subcommand("phantom", "Write the tooth phantom to a .vdb or .nrrd file");
  struct Args {
    std::string out;
    std::vector<int> size;
    double voxel = 0.0;
    bool socket = false;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("--out", args->out, "Output file (.vdb or .nrrd)")->required();
  cmd->add_option("--size", args->size, "Voxels along X,Y,Z (default 256,256,176)")->delimiter(',')->expected(3);
  cmd->add_option("--voxel", args->voxel, "Voxel size in metres (default: keeps the 25.6 mm extent)");
  cmd->add_flag("--socket", args->socket, "Surround the roots with alveolar bone");
  cmd->callback([args, &result] {
    std::string url = "phantom:tooth?socket=" + std::string(args->socket ? "1" : "0");
    if (!args->size.empty())
      url += "&size=" + std::to_string(args->size[0]) + "," + std::to_string(args->size[1]) + "," +
             std::to_string(args->size[2]);
    if (args->voxel != 0.0) url += "&voxel=" + std::to_string(args->voxel);
    try {
      const std::filesystem::path out(args->out);
      const std::string ext = out.extension().string();
      if (ext != ".vdb" && ext != ".nrrd")
        throw VolumeError(args->out + ": unknown output format '" + ext + "' (expected .vdb or .nrrd)");
      const auto t0 = std::chrono::steady_clock::now();
      VoxelVolume v = makeToothPhantom(parsePhantomUrl(url));
      const auto t1 = std::chrono::steady_clock::now();
      if (ext == ".vdb") writeVdb(v, out);
      else writeNrrd(v, out, /*gzip=*/true);
      std::cout << "wrote " << args->out << ": " << v.dims().x << "x" << v.dims().y << "x" << v.dims().z
                << " voxels of " << v.voxelSize().x * 1e3 << " mm (built in "
                << std::chrono::duration<double, std::milli>(t1 - t0).count() << " ms)\n";
      result = kExitOk;
    } catch (const VolumeError& e) {
      std::cerr << "millsim phantom: error: " << e.what() << "\n";
      result = kExitBadInput;
    }
  });
}

}  // namespace millsim::app
