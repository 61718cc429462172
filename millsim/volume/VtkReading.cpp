#include "millsim/volume/VtkReading.h"

#include <algorithm>
#include <stdexcept>

#include <vtkAlgorithm.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkExecutive.h>
#include <vtkType.h>

#include "millsim/volume/ReaderLimits.h"
#include "millsim/volume/VolumeBuilder.h"

namespace millsim::vtkio {

void VtkMessages::collect(vtkObject*, unsigned long, void* self, void* call) {
  if (!call) return;
  std::string m = static_cast<const char*>(call);
  const std::size_t p = m.find("): ");  // drop "file.cxx:123 vtkClass (0x...): "
  if (p != std::string::npos) m = m.substr(p + 3);
  m = trim(m.substr(0, m.find('\n')));  // first line: the executive appends a request dump
  auto& t = static_cast<VtkMessages*>(self)->text;
  // The executive's "Algorithm ... returned failure" only repeats that the reader failed.
  if (m.rfind("Algorithm ", 0) == 0 && !t.empty()) return;
  t += (t.empty() ? "" : "; ") + m;
}

void VtkMessages::watch(vtkAlgorithm* a) {
  a->AddObserver(vtkCommand::ErrorEvent, command);
  a->AddObserver(vtkCommand::WarningEvent, command);
  a->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, command);
}

void appendFloats(vtkDataArray* a, VolumeBuilder& out) {
  const std::size_t n = std::size_t(a->GetNumberOfTuples()) * std::size_t(a->GetNumberOfComponents());
  switch (a->GetDataType()) {
    vtkTemplateMacro({
      const auto* p = static_cast<const VTK_TT*>(a->GetVoidPointer(0));
      for (std::size_t i = 0; i < n && out.room() > 0;) {
        const std::size_t k = std::min(n - i, out.room());
        float* to = out.next();
        for (std::size_t j = 0; j < k; ++j) to[j] = static_cast<float>(p[i + j]);
        out.advance(k);
        i += k;
      }
    });
    default: throw std::runtime_error(std::string("unsupported scalar type ") + a->GetDataTypeAsString());
  }
}

}  // namespace millsim::vtkio
