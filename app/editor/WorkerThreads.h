#pragma once
// The OpenMP thread count of the editor's background work (simulation cache, optimiser). The
// UI thread and the GL driver (llvmpipe draws on the CPU) need a core of their own: with every
// core given to OpenMP, its spinning workers and the UI fight over the cores and a 2-core
// machine runs an optimisation 15x slower than with one worker. Call at the start of a worker
// thread (the setting is per thread).

namespace weft::editor {

// Sets the calling thread's OpenMP team size to the processor count minus one (at least 1),
// or to $WEFT_EDITOR_THREADS when that is set to a positive number.
void useWorkerThreads();

}  // namespace weft::editor
