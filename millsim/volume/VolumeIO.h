#pragma once
// Reading and writing volume files. Every reader returns a VoxelVolume in
// index space with the voxel size in metres (file spacings are millimetres in
// all supported formats and are converted), or throws VolumeError naming the
// file and the problem. Readers check sizes before allocating.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "millsim/volume/VoxelVolume.h"

namespace millsim {

struct MeshVoxelOptions;

struct LoadedVolume {
  VoxelVolume volume;
  std::string format;  // "vdb", "nrrd", "metaimage", "vti", "dicom", "phantom", "STL", "binary STL", "OBJ", "PLY"
  std::string source;  // the file, folder or phantom url that was read
  // A surface mesh's parts as labels (part i is label i + 1) and their names; a short account of what was voxelised.
  std::optional<VoxelVolume> labels = std::nullopt;
  std::vector<std::string> parts = {};
  std::string account = {};
};

// Dispatches on the url: "phantom:tooth[?options]" (see ToothPhantom.h), a
// folder (DICOM series), or a file by extension: .vdb, .nrrd/.nhdr, .mha/.mhd,
// .vti, .dcm; a surface mesh (.stl, .obj, .ply), voxelised with `mesh`'s
// options (MeshVolume.h; without them a mesh is an error saying a voxel size
// is needed). Relative paths are resolved against baseDir. Density values at
// or below airValue become air (the sparse background).
// `voxelSize` (0: none) is the VolumeObject's, for a format that may carry none (slices).
LoadedVolume loadVolume(const std::string& url, const std::filesystem::path& baseDir, float airValue,
                        const MeshVoxelOptions* mesh = nullptr, glm::dvec3 voxelSize = glm::dvec3(0.0));

VoxelVolume readVdb(const std::filesystem::path& file, float airValue);
VoxelVolume readNrrd(const std::filesystem::path& file, float airValue);       // .nrrd, .nhdr; raw or gzip
// readMetaImage, readVti and readDicom are in libmillsim_medical (VTK, GDCM),
// opened on the first call (MedicalModule.h); a VolumeError says so when it
// cannot be.
VoxelVolume readMetaImage(const std::filesystem::path& file, float airValue);  // .mha, .mhd
VoxelVolume readVti(const std::filesystem::path& file, float airValue);        // VTK XML image data
// A folder of CT slices (or one slice file): rescale slope/intercept applied,
// slices ordered by position along the slice normal; refuses non-CT modalities.
VoxelVolume readDicom(const std::filesystem::path& fileOrFolder, float airValue);
// A micro-CT slice stack: a folder of greyscale TIFF slices (sorted naturally:
// slice_2 before slice_10), a printf-style pattern ("slices/img_%04d.tif",
// from the first index of 0–9 that exists to the last consecutive one), or
// the pages of one .tif; 8 or 16-bit (or 32-bit float), one channel; at most
// 20 000 slices. The pixel size is `voxelSize` when not 0, else a SkyScan
// .log's "Image Pixel Size (um)" beside the slices, else the TIFF resolution
// tags; slices are as far apart as pixels are wide. Values are the densities.
VoxelVolume readSliceStack(const std::filesystem::path& folderPatternOrTiff, float airValue,
                           glm::dvec3 voxelSize = glm::dvec3(0.0));
// Several surface meshes voxelised together as the parts of one volume (a
// file of one part is the part of its stem's name: enamel.stl is 'enamel').
LoadedVolume loadMeshParts(const std::vector<std::string>& urls, const std::filesystem::path& baseDir,
                           const MeshVoxelOptions& mesh);
// True for a path with one printf integer field (%d, %04d): a slice-stack pattern.
bool isSliceStackPattern(const std::string& path);
// True for a slice image a stack may hold, by its extension: .tif, .tiff, .png or .bmp.
bool isSliceImageFile(const std::filesystem::path& path);

// Throws VolumeError "FILE: no such file" or "FILE: is a folder, not WHAT".
void requireFile(const std::filesystem::path& file, const std::string& what);

// Writers used by `millsim phantom` and the tests. Spacing is written in millimetres.
void writeVdb(const VoxelVolume& volume, const std::filesystem::path& file);
void writeNrrd(const VoxelVolume& volume, const std::filesystem::path& file, bool gzip = false);

}  // namespace millsim
