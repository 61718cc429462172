// The table loadMedicalModule() finds in libmillsim_medical.
#include "millsim/volume/MedicalModule.h"

namespace {

const millsim::MedicalModule kModule{millsim::kMedicalAbiVersion, &millsim::medical::readMetaImage,
                                     &millsim::medical::readVti, &millsim::medical::readDicom};

}  // namespace

extern "C" __attribute__((visibility("default"))) const millsim::MedicalModule* millsim_medical_module() {
  return &kModule;
}
