#include "millsim/volume/VolumeObject.h"

#include "millsim/volume/VolumeError.h"
#include "millsim/volume/VolumeModule.h"

namespace millsim {

VolumeObject::VolumeObject() = default;
VolumeObject::~VolumeObject() = default;

const NodeType& VolumeObject::type() {
  static const NodeType t = makeNodeType<VolumeObject>(
      "VolumeObject", "children", "MillSim volumes",
      "A CT voxel volume that is felt, milled and drawn, centred on its local origin.");
  return t;
}

const std::string VolumeObject::kNoFormat;

void VolumeObject::initialize(DiagnosticSink& sink) {
  if (url.get().empty()) {
    sink.error(location(), "VolumeObject has an empty url (expected a volume file, a DICOM folder or phantom:tooth)");
    return;
  }
  if (!(isoValue.get() > airValue.get())) {
    sink.error(location(), "VolumeObject isoValue " + formatNumber(isoValue.get()) + " must be above airValue " +
                               formatNumber(airValue.get()));
    return;
  }
  std::string error;
  const VolumeModule* module = loadVolumeModule(error);
  if (!module) {
    sink.error(location(), "VolumeObject cannot load volumes: " + error);
    return;
  }
  contents_ = module->load(*this, sink);
}

PointShell& VolumeObject::pointShell(int scale) {
  if (!contents_) throw VolumeError("VolumeObject has no volume loaded");
  return contents_->pointShell(scale);
}

}  // namespace millsim
