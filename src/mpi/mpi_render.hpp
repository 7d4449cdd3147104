// A render over the ranks of an MPI job (mpirun -np N wavepath render ...).
//
// Every rank opens its own devices (--device, on its machine) and the scene.
// Rank 0 runs the command as usual, with the other ranks attached to its
// MultiDeviceRenderer as RenderPeers: their device threads ask rank 0 for
// chunks of samples when they need work (so a slow machine takes less), and
// at the end of each render() call each rank sends its film, which rank 0
// adds in rank order. Only rank 0 writes outputs.
//
// The protocol, by message tag (rank r and rank 0):
//   start   r -> 0  JSON {ok, devices, error, fingerprint}: could r open its
//                   devices and the scene, and what does it render (scene
//                   content, film shape, options: render/checkpoint.hpp)?
//   go      0 -> r  1 to render, 0 to give up (some rank could not start, or
//                   renders something else than rank 0)
//   request r -> 0  samples per pixel completed since r's last request
//   reply   0 -> r  {kind, first, count}: a chunk; "done" (this call has no
//                   more: send the film); "end" (the render is over)
//   film    r -> 0  the call's film (Film::packed_*), or an empty one
//   failed  r -> 0  r's every device failed: the job ends with that error
//   bye     r -> 0  JSON: r's devices' shares, for the profile
// There is no fault tolerance: MPI cannot go on without a lost rank, so a
// rank that fails ends the job (docs/multi-device.md; long jobs should
// checkpoint).
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "mpi/mpi_job.hpp"
#include "render/integrator_options.hpp"
#include "render/multi_device.hpp"
#include "scene/scene.hpp"

namespace wp {

// On rank 0: opens the local devices, hears every rank's start-up report,
// and returns the renderer with the other ranks attached; throws the first
// rank's error ("rank 2 of 4 (host): no OpenCL device ...") if any failed,
// or names the first rank whose fingerprint differs from rank 0's and what
// differs ("rank 1 of 2 (host) does not render what rank 0 does: its
// options differ from rank 0's: 'estimator=...' where rank 0 has ...").
std::unique_ptr<MultiDeviceRenderer> open_mpi_renderer(MpiJob& job, const Scene& scene,
                                                       const std::string& devices,
                                                       const IntegratorOptions& options,
                                                       bool profiling);

// On any other rank: the whole of its part, until rank 0 says the end; the
// exit status (0: it writes no file and no error; rank 0 reports them and
// sets the job's exit status).
int run_mpi_worker(MpiJob& job, const std::function<Scene()>& load_scene,
                   const std::string& devices, const IntegratorOptions& options);

// Rank 0 failed before open_mpi_renderer: tells the waiting ranks to give up.
void refuse_start(MpiJob& job);

} // namespace wp
