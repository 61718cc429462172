#pragma once
// VolumeObject: a CT voxel volume in the scene — the object that is felt, milled
// and drawn. Placed like X3D's VolumeData: centred on its local origin, under
// any Transforms. The voxels live in a VoxelVolume (OpenVDB), held with their
// tissues and point shells by a VolumeContents that libmillsim makes
// (VolumeModule.h: this node's library does not link OpenVDB); the point
// shell for Algorithm #3 is built only when a renderer asks for it.
#include <algorithm>
#include <memory>
#include <string>
#include <utility>

#include "millsim/core/NodeKinds.h"
#include "millsim/volume/Tissue.h"
#include "millsim/volume/VolumeContents.h"
#include "millsim/volume/VoxelSizeRange.h"

namespace millsim {

class VolumeObject : public ChildNode {
public:
  VolumeObject();
  ~VolumeObject() override;
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFString url{this, "url", Access::InitializeOnly, {"phantom:tooth"},
               "Volume sources, first loadable wins: a .vdb, .nrrd/.nhdr, .mha/.mhd, .vti or .dcm file, a folder "
               "of DICOM slices, a micro-CT stack of greyscale TIFF, PNG or BMP slices (a folder, a pattern such as "
               "slices/img_%04d.tif, or one multi-page .tif; the pixel size from voxelSize, a SkyScan .log, the "
               "TIFF tags or the PNG pHYs chunk), phantom:tooth[?size=X,Y,Z&voxel=M&socket=0|1] (in an X3D file each & is written "
               "&amp;), or a closed surface mesh (.stl, .obj, .ply: its parts, an OBJ's groups or an STL's solids, "
               "become labels Tissues name) voxelised at voxelSize; several mesh urls are the parts of one volume "
               "(enamel.stl is the part 'enamel'), not fallbacks. Every density must be a finite number."};
  SFFloat isoValue{this, "isoValue", Access::InitializeOnly, 700.f,
                   "Density above which a point is inside the object (Hounsfield-like units).", Range::closed(-1e9, 1e9)};
  SFFloat airValue{this, "airValue", Access::InitializeOnly, -1000.f,
                   "Density of air; values at or below it are stored as the sparse background.", Range::closed(-1e9, 1e9)};
  SFVec3f voxelSize{this, "voxelSize", Access::InitializeOnly, glm::vec3(0.f),
                    "Voxel size (m), each 1 µm to 10 mm; 0 0 0 takes it from the file (millimetres there). A mesh "
                    "url needs it, the same along x, y and z.",
                    Range::closed(0, kMaxVoxelSize).in(quantity::length)};
  SFFloat meshUnit{this, "meshUnit", Access::InitializeOnly, 1.f,
                   "The length one unit of a mesh url's coordinates stands for (m): STL, OBJ and PLY carry no unit. "
                   "0.001 for a mesh in millimetres, as dental scanners write them.",
                   Range::closed(1e-9, 1e3).in(quantity::length)};
  MFNodeOf<Tissue> tissues{this, "tissues", Access::InitializeOnly,
                           "The volume's materials (Tissue nodes): the first that matches a voxel is its tissue; "
                           "material no tissue matches is cut with hardness 1."};
  MFString labelUrl{this, "labelUrl", Access::InitializeOnly, {},
                    "A label volume, voxel for voxel with url, for tissues chosen by label: a volume file as for "
                    "url, or phantom:tooth-labels[?the phantom's options] (1 enamel, 2 dentin, 3 pulp, 4 cementum, "
                    "5 bone, 6 ligament)."};
  SFBool millable{this, "millable", Access::InputOutput, true, "Whether the burr removes material; live: a change applies from the next frame."};
  SFInt32 millingBudget{this, "millingBudget", Access::InitializeOnly, 0,
                        "Densities the burr's stamps may read in one haptic frame (0: no limit, every stamp in its "
                        "frame). A stamp reads about (burr radius / voxel)² of them (600 for a 0.6 mm burr at 0.1 mm "
                        "voxels, 8000 at 25 µm); one the budget does not cover is finished over the next frames, the "
                        "newest burr position next, so a frame's milling costs about the same at every resolution "
                        "while the renderers feel each stamp whole from its first frame (not with a tissue of "
                        "hardness 0). Off by default: docs/algorithms.md, \"Milling at fine voxels\".",
                        Range::closed(0, 100000000)};
  SFFloat removedVolume{this, "removedVolume", Access::OutputOnly, 0.f, "Material removed so far (m³)."};
  SFString loadedUrl{this, "loadedUrl", Access::OutputOnly, "", "The url that was loaded."};

  void initialize(DiagnosticSink& sink) override;

  // Null until initialize() loaded a volume.
  VoxelVolume* volume() { return contents_ ? &contents_->voxels() : nullptr; }
  const VoxelVolume* volume() const { return contents_ ? &std::as_const(*contents_).voxels() : nullptr; }
  const std::string& format() const { return contents_ ? contents_->format() : kNoFormat; }
  // The volume's extent in its local frame (m): dimensions x voxel size; zero until loaded.
  glm::dvec3 size() const { return contents_ ? contents_->size() : glm::dvec3(0.0); }
  // The loaded voxel's edges along x, y and z in the local frame (m); zero until loaded.
  glm::dvec3 voxelEdges() const { return contents_ ? contents_->voxelEdges() : glm::dvec3(0.0); }
  // The smallest voxel edge (m); zero until loaded.
  double voxelEdge() const {
    const glm::dvec3 e = voxelEdges();
    return std::min({e.x, e.y, e.z});
  }
  // The point shell at an integer scale, built on first request. Throws
  // VolumeError when no volume is loaded.
  PointShell& pointShell(int scale);
  // The voxels' tissues; null when the volume has no Tissue nodes.
  const TissueMap* tissueMap() const { return contents_ ? contents_->tissueMap() : nullptr; }
  bool hasPointShell(int scale) const { return contents_ && contents_->hasPointShell(scale); }

private:
  static const std::string kNoFormat;
  std::unique_ptr<VolumeContents> contents_;
};

}  // namespace millsim
