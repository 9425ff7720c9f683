#ifndef mpm_stages_staged_run_h
#define mpm_stages_staged_run_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <functional>
#include <string>

namespace mpm
{
  using namespace dealii;

  /**
   * Run the scene in @p prm: as one Simulation, or stage after stage. A
   * stage starts from the checkpoint the one before wrote at its end, with
   * its changes applied to the scene, as a restart with other parameters
   * would (so a stage's start is as tested as a restart). @p restart: a
   * checkpoint to continue from, within or across stages (the stage is in
   * its state). @p read_scene fills a fresh ParameterHandler with the scene
   * as given: every stage's parameters are read before the first step, so
   * that a mistake in the last stage is not found hours into the run.
   */
  template <int dim>
  void
  run_scene(ParameterHandler                              &prm,
            MPI_Comm                                       comm,
            const std::string                             &restart,
            const std::function<void(ParameterHandler &)> &read_scene);
} // namespace mpm

#endif
