// Built only into ThreadSanitizer builds (MILLSIM_SANITIZE=thread).
//
// Debian's libtbb is not instrumented, so TSan cannot see the join at the end
// of a parallel_for and reports the caller's later reads of what the workers
// wrote (OpenVDB's CopyFromDense, the tooth phantom) as races; the workers'
// stacks are often lost, so suppressions cannot name them reliably. Running
// TBB on the calling thread removes these false reports at their cause; TSan
// then checks what it is here for: MillSim's own haptic, graphics, window and
// scene threads. A namespace-scope object because it must exist before the
// first OpenVDB call, whichever program (millsim or a test) loads the library.
#include <tbb/global_control.h>

namespace {
const tbb::global_control serialTbb{tbb::global_control::max_allowed_parallelism, 1};
}  // namespace
