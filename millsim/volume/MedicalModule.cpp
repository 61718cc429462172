// The table loadMedicalModule() finds in libmillsim_medical.
#include "millsim/volume/MedicalModule.h"

namespace {

const millsim::MedicalModule kModule{millsim::kMedicalAbiVersion, &millsim::medical::readMetaImage,
                                     &millsim::medical::readVti, &millsim::medical::readDicom,
                                     &millsim::medical::readSliceStack};

}  // namespace

// Typed as the loader calls it (SiblingLibrary: const void* (*)()): a call through
// another function type is undefined behaviour (clang's -fsanitize=function).
extern "C" __attribute__((visibility("default"))) const void* millsim_medical_module() {
  return &kModule;
}
