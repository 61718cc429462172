#include "millsim/x3d/H3dNodeNames.h"

#include <iterator>

namespace millsim {

namespace {
// Names only (public node names of H3DAPI's and MedX3D's documentation), for
// messages; no H3DAPI code is used. DeviceInfo is read by the loader itself.
constexpr H3dNodeName kNames[] = {
    {"GodObjectRenderer", H3dNodeKind::Renderer},   {"RuspiniRenderer", H3dNodeKind::Renderer},
    {"Chai3DRenderer", H3dNodeKind::Renderer},      {"OpenHapticsRenderer", H3dNodeKind::Renderer},
    {"LayeredRenderer", H3dNodeKind::Renderer},
    {"NiFalconDevice", H3dNodeKind::Device},        {"HapticMasterDevice", H3dNodeKind::Device},
    {"HaptionDevice", H3dNodeKind::Device},
    {"EntactDevice", H3dNodeKind::Device},          {"SimballDevice", H3dNodeKind::Device},
    {"QuanserDevice", H3dNodeKind::Device},         {"MLHIDevice", H3dNodeKind::Device},
    {"FakeHapticsDevice", H3dNodeKind::Device},     {"SmoothSurface", H3dNodeKind::Other},
    {"FrictionalSurface", H3dNodeKind::Other},      {"MagneticSurface", H3dNodeKind::Other},
    {"DepthMapSurface", H3dNodeKind::Other},        {"HapticTexturesSurface", H3dNodeKind::Other},
    {"OpenHapticsSurface", H3dNodeKind::Other},     {"Chai3DSurface", H3dNodeKind::Other},
    {"ForceField", H3dNodeKind::Other},             {"SpringEffect", H3dNodeKind::Other},
    {"PositionFunctionEffect", H3dNodeKind::Other}, {"ViscosityEffect", H3dNodeKind::Other},
    {"TimeFunctionEffect", H3dNodeKind::Other},     {"HapticLayeredGroup", H3dNodeKind::Other},
    {"HapticShapeConstraint", H3dNodeKind::Other},
    {"FitToBoxTransform", H3dNodeKind::Other},      {"PythonScript", H3dNodeKind::Other},
    {"DynamicTransform", H3dNodeKind::Other},       {"GlobalSettings", H3dNodeKind::Other},
    {"DefaultAppearance", H3dNodeKind::Other},      {"HapticsOptions", H3dNodeKind::Other},
    {"GraphicsOptions", H3dNodeKind::Other},        {"GraphicsCachingOptions", H3dNodeKind::Other},
    {"DebugOptions", H3dNodeKind::Other},           {"CollisionOptions", H3dNodeKind::Other},
    {"StereoInfo", H3dNodeKind::Other},             {"MouseSensor", H3dNodeKind::Other},
    {"WiimoteSensor", H3dNodeKind::Other},
    {"FullscreenRectangle", H3dNodeKind::Other},    {"H3DWindowNode", H3dNodeKind::Other},
    {"GLUTWindow", H3dNodeKind::Other},             {"WxWidgetsWindow", H3dNodeKind::Other},
    {"FrameBufferTextureGenerator", H3dNodeKind::Other}, {"ShaderAtomicCounter", H3dNodeKind::Other},
    {"MedX3DDemoSettings", H3dNodeKind::Other},     {"MultiVolumeData", H3dNodeKind::Other},
};
}  // namespace

const H3dNodeName* findH3dNode(std::string_view name) {
  for (const H3dNodeName& n : kNames)
    if (n.name == name) return &n;
  return nullptr;
}

}  // namespace millsim
