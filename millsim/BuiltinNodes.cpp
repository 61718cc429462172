// The explicit list of node types MillSim provides. New node types are added
// here (or, for integrators, in a plugin's entry point), never by static
// initialisers.
#include "millsim/core/NodeRegistry.h"
#include "millsim/devices/AnyDevice.h"
#include "millsim/devices/AresDevice.h"
#include "millsim/devices/DeviceChecks.h"
#include "millsim/devices/HandDevice.h"
#include "millsim/devices/MouseDevice.h"
#include "millsim/devices/FalconDevice.h"
#include "millsim/devices/ForceDimensionDevice.h"
#include "millsim/devices/PhantomDevice.h"
#include "millsim/devices/SpaceMouseDevice.h"
#include "millsim/devices/SpaceWareSensor.h"
#include "millsim/devices/TrajectoryDevice.h"
#include "millsim/haptics/MillTool.h"
#include "millsim/lesson/ForbiddenRegion.h"
#include "millsim/lesson/MillingTarget.h"
#include "millsim/lesson/RegionChecks.h"
#include "millsim/renderers/BarbicRenderer.h"
#include "millsim/renderers/LineProxyRenderer.h"
#include "millsim/renderers/SurfacePointRenderer.h"
#include "millsim/volume/VolumeObject.h"

namespace millsim {

void registerBuiltinNodes(NodeRegistry& r) {
  registerStandardNodes(r);
  for (const NodeType* t : {&VolumeObject::type(), &Tissue::type(), &MillTool::type(), &LineProxyRenderer::type(),
                            &SurfacePointRenderer::type(), &BarbicRenderer::type(), &TrajectoryDevice::type(),
                            &HandDevice::type(), &AresDevice::type(), &MouseDevice::type(), &AnyDevice::type(), &PhantomDevice::type(), &ForceDimensionDevice::type(), &FalconDevice::type(),
                            &SpaceMouseDevice::type(), &SpaceWareSensor::type(), &MillingTarget::type(),
                            &ForbiddenRegion::type()})
    r.add(*t);
  r.addSceneCheck(&checkDevices);
  r.addSceneCheck(&checkRegions);
}

NodeRegistry builtinRegistry() {
  NodeRegistry r;
  registerBuiltinNodes(r);
  return r;
}

}  // namespace millsim
