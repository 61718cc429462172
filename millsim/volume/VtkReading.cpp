#include "millsim/volume/VtkReading.h"

#include <stdexcept>

#include <vtkAlgorithm.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkExecutive.h>
#include <vtkType.h>

#include "millsim/volume/ReaderLimits.h"

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

std::vector<float> toFloats(vtkDataArray* a) {
  const vtkIdType n = a->GetNumberOfTuples() * a->GetNumberOfComponents();
  std::vector<float> v(static_cast<std::size_t>(n));
  switch (a->GetDataType()) {
    vtkTemplateMacro({
      const auto* p = static_cast<const VTK_TT*>(a->GetVoidPointer(0));
      for (vtkIdType i = 0; i < n; ++i) v[std::size_t(i)] = static_cast<float>(p[i]);
    });
    default: throw std::runtime_error(std::string("unsupported scalar type ") + a->GetDataTypeAsString());
  }
  return v;
}

}  // namespace millsim::vtkio
