// millsim devices: which haptic devices this machine can open, and what each
// can do, without running a scene or opening a window: the vendor libraries
// MillSim loads at run time (where each was found, or what to install) and
// the devices behind them.
#include <iomanip>
#include <iostream>
#include <sstream>

#include "Commands.h"
#include "millsim/devices/AresDevice.h"
#include "millsim/driver/ForceDimensionDriver.h"
#include "millsim/driver/OpenHapticsDriver.h"
#include "millsim/driver/SpaceNav.h"

namespace millsim::app {

void addDevicesCommand(CLI::App& app, int& result) {
  auto* cmd = app.add_subcommand("devices", "List the haptic devices and vendor libraries this machine has");
  cmd->callback([&result] {
    std::ostringstream out;
    out << "ARES (AresDevice; AnyDevice tries it first):\n";
    AresDevice ares;
    try {
      ares.findAres();
      out << "  " << std::hex << std::setfill('0') << std::setw(4) << ares.vendorId.get() << ":" << std::setw(4)
          << ares.productId.get() << std::dec << std::setfill(' ')
          << " found (its USB interface can be claimed)\n";
    } catch (const DeviceError& e) {
      std::string what = e.what();
      for (std::size_t at = what.find('\n'); at != std::string::npos; at = what.find('\n', at + 3))
        what.replace(at, 1, "\n  ");
      out << "  " << what << "\n";
    }
    out << "Force Dimension (ForceDimensionDevice, FalconDevice; AnyDevice tries it second):\n";
    const ForceDimensionProbe fd = probeForceDimension(ForceDimensionSelector{});
    if (fd.library.empty()) {
      out << "  library: not found: " << fd.error << "\n";
    } else {
      out << "  library: " << fd.library << " (" << fd.version << "), " << fd.deviceCount << " device(s) attached\n";
      if (!fd.device) {
        out << "  first device: " << fd.error << "\n";
      } else {
        const ForceDimensionCapabilities& c = fd.capabilities;
        out << "  first device: " << (c.model.empty() ? "(no model name)" : c.model) << ", "
            << (c.sensesOrientation ? "6-DOF in" : "3-DOF in (no orientation)") << ", "
            << (c.outputsTorque ? "force and torque out" : "force out only");
        if (c.maxForce > 0.0) out << ", force limit " << c.maxForce << " N";
        out << "\n";
      }
    }
    out << "OpenHaptics (PhantomDevice; AnyDevice tries it third):\n";
    const OpenHapticsProbe hd = probeOpenHaptics("");
    if (hd.library.empty()) {
      out << "  library: not found: " << hd.error << "\n";
    } else {
      out << "  library: " << hd.library << "\n";
      if (!hd.device) {
        out << "  default device: " << hd.error << "\n";
      } else {
        const OpenHapticsCapabilities& c = hd.capabilities;
        out << "  default device: " << (c.model.empty() ? "(no model name)" : c.model) << ", "
            << (c.outputDof >= 6 ? "6-DOF output (MillSim sends force only)" : "3-DOF force output")
            << ", nominal max force " << c.maxForce << " N (continuous " << c.maxContinuousForce
            << " N), max stiffness " << c.maxStiffness << " N/m; calibration " << hd.calibration << "\n";
      }
    }
    out << "3D mice (SpaceMouseDevice, SpaceWareSensor):\n";
    try {
      const std::shared_ptr<SpaceNav> nav = SpaceNav::open();
      out << "  spacenavd: connected; device: " << (nav->deviceName().empty() ? "(not named)" : nav->deviceName())
          << "\n";
    } catch (const DeviceError& e) {
      out << "  spacenavd: " << e.what() << "\n";
    }
    std::cout << out.str();
    result = kExitOk;
  });
}

}  // namespace millsim::app
