// Which devices `render` runs on: every device of --device, and, in an MPI
// job (mpirun -np N wavepath render ...), every rank's devices, with rank 0
// handing out the chunks and writing the outputs (docs/multi-device.md).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "render/multi_device.hpp"
#include "scene/scene.hpp"

namespace wp {

// On a rank other than 0 of an MPI job: renders the chunks rank 0 hands out
// until it says the render is over, writes nothing, and returns the exit
// status. Without MPI, or on rank 0: nothing, and run_render goes on.
std::optional<int> run_render_as_mpi_worker(const RenderCommand& command);

// The renderer for --device (select_devices), with the other ranks attached
// on rank 0 of an MPI job; throws the first error of any rank that could not
// open its devices or the scene. Outside an MPI job the scene is prepared
// once for every device and its triangles are freed once flattened
// (prepare_scene_releasing_triangles): the caller must not need them after.
std::unique_ptr<MultiDeviceRenderer> open_renderer(const RenderCommand& command, Scene& scene,
                                                   bool profiling);

// Every device's name, in the order of shares() (for the image's metadata).
std::vector<std::string> device_names(const MultiDeviceRenderer& renderer);

// With more than one device: a line per device, its share of the samples,
// samples/s and idle time (stdout).
void print_device_shares(const MultiDeviceRenderer& renderer);

} // namespace wp
