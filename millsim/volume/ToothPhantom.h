#pragma once
// The embedded default volume: a deterministic, anatomically plausible lower
// molar in Hounsfield-like units — enamel crown, dentin, pulp chamber with
// horns, two roots with canals, and an optional bone socket with a periodontal
// ligament gap. The tooth's long axis is +Y (crown up, the X3D "up"), so a
// tool coming from above mills the occlusal surface.
#include <string>

#include <glm/vec3.hpp>

#include "millsim/volume/VoxelVolume.h"

namespace millsim {

struct ToothPhantomOptions {
  glm::ivec3 dims{256, 256, 176};   // as the paper's CT data
  double voxelSize = 0.1e-3;        // metres; the tooth is about 11 x 21 x 10 mm
  bool socket = false;              // surround the roots with bone
};

// Hounsfield-like values the phantom uses.
struct ToothDensities {
  static constexpr float air = -1000.f;
  static constexpr float softTissue = 40.f;  // pulp, ligament
  static constexpr float bone = 900.f;
  static constexpr float dentin = 1600.f;
  static constexpr float enamel = 2800.f;
};

// Labels of the phantom's tissues (phantom:tooth-labels): 0 is air.
enum ToothLabel : int {
  kToothEnamel = 1,
  kToothDentin = 2,
  kToothPulp = 3,
  kToothCementum = 4,
  kToothBone = 5,
  kToothLigament = 6,
};

// Parses "phantom:tooth[?size=X,Y,Z&voxel=M&socket=0|1]". Throws VolumeError.
// (In an X3D attribute each '&' is written "&amp;"; libxml2 turns it back.)
ToothPhantomOptions parsePhantomUrl(const std::string& url);
// Builds the phantom; the size is scaled so the tooth fills the same fraction
// of the volume whatever the voxel count (voxelSize then follows from dims).
VoxelVolume makeToothPhantom(const ToothPhantomOptions& options);
// The phantom's tissue labels (ToothLabel), voxel for voxel with
// makeToothPhantom(options): every voxel with material there has a label.
VoxelVolume makeToothPhantomLabels(const ToothPhantomOptions& options);
// Both at once, from one evaluation of the tooth's distances per voxel (what a
// scene whose url and labelUrl name the same phantom loads): each equal voxel
// for voxel to the one built alone.
struct ToothPhantomWithLabels {
  VoxelVolume densities, labels;
};
ToothPhantomWithLabels makeToothPhantomWithLabels(const ToothPhantomOptions& options);
// "phantom:tooth-labels[?the phantom's options]": the labels of the phantom
// with those options. Whether a url names them, its options, and reading it
// (VolumeError, naming the labels url).
bool isPhantomLabelsUrl(const std::string& url);
ToothPhantomOptions parsePhantomLabelsUrl(const std::string& url);
VoxelVolume loadPhantomLabels(const std::string& url);
// Density of the phantom at a point (metres, tooth frame centred like the volume).
float toothPhantomDensity(const glm::dvec3& p, bool socket);
// The value makeToothPhantom (makeToothPhantomLabels) gives voxel ijk, computed
// alone: what the sparse build must equal voxel for voxel.
float toothPhantomVoxel(const ToothPhantomOptions& options, glm::ivec3 ijk);
int toothPhantomLabelVoxel(const ToothPhantomOptions& options, glm::ivec3 ijk);

}  // namespace millsim
