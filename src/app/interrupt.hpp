// Ctrl-C and SIGTERM during a long render. Once the render loop has begun
// (begin_interruptible_work), the first one asks the render to stop at the
// next wave boundary, so that every pixel has the same number of samples and
// the outputs are written with what was done; a second one ends the process
// at once, removing the temporary file of a write in progress (util/file.hpp)
// so that nothing half-written is left. Before the loop has begun (loading
// the scene, building kernels, reading a checkpoint) there is nothing to
// save, and the first signal ends the process at once.
#pragma once

namespace wp {

// Installs the SIGINT and SIGTERM handlers; call once, before any work.
void install_interrupt_handlers();

// From here on the first signal stops the render at a wave boundary instead
// of ending the process; call as the render loop starts.
void begin_interruptible_work();

// The first signal's effect without a signal (the preview's stop button):
// the render stops at the next wave boundary, writes its outputs and exits
// as after Ctrl-C (interrupt_signal() is then SIGINT). Callable from any
// thread; returns false if a stop was already asked for.
bool request_interrupt();

// Whether a first signal (or request) has arrived, and which (0: none).
bool interrupt_requested();
int interrupt_signal();

} // namespace wp
