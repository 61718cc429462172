#pragma once
// Shared by the VTK-based volume readers (MetaImage, VTI): turning VTK's
// printed errors into exception text, and converting its scalar arrays.
// Internal to millsim/volume (listed in cmake/private-headers.txt): includes VTK headers.
#include <string>

#include <vtkCallbackCommand.h>
#include <vtkNew.h>

class vtkAlgorithm;
class vtkDataArray;
class vtkObject;

namespace millsim {
class VolumeBuilder;
}

namespace millsim::vtkio {

// Collects what VTK would print, so that it goes into the exception instead.
struct VtkMessages {
  std::string text;
  vtkNew<vtkCallbackCommand> command;
  VtkMessages() {
    command->SetClientData(this);
    command->SetCallback(&VtkMessages::collect);
  }
  void watch(vtkAlgorithm* a);

private:
  static void collect(vtkObject*, unsigned long, void* self, void* call);
};

// Every value of a one-component VTK array, as float, into the volume being
// built (a slab at a time, no dense float copy); throws std::runtime_error on
// unsupported types.
void appendFloats(vtkDataArray* a, VolumeBuilder& out);

}  // namespace millsim::vtkio
