#pragma once
// A report after every step of a forward or backward pass, for a progress display and for
// cancelling within an evaluation: the phase, which backward pass of a gradient it is (error
// control makes pairs: GradientErrorControl.h; always 1 forward), the steps done and the total.
// It may throw to abandon the pass; the exception leaves the pass and whatever called it.

#include <functional>

namespace weft {

enum class PassPhase { Forward, Backward };

using StepProgress = std::function<void(PassPhase phase, int pass, int done, int total)>;

}  // namespace weft
