#include <mpm/checkpoint.h>
#include <mpm/parameters.h>
#include <mpm/simulation.h>
#include <mpm/stages/staged_run.h>

#include <exception>

namespace mpm
{
  namespace
  {
    /// Run one Simulation. It (and its TimerOutput, which communicates in
    /// its destructor) is destroyed normally before a failure is passed
    /// on.
    template <int dim>
    RunEnding
    run_one(ParameterHandler    &prm,
            MPI_Comm             comm,
            const std::string   &restart,
            const StagePosition &stage)
    {
      std::exception_ptr failure;
      RunEnding          ending;
      {
        Simulation<dim> simulation(prm, comm, restart, stage);
        try
          {
            ending = simulation.run();
          }
        catch (...)
          {
            failure = std::current_exception();
          }
      }
      if (failure)
        std::rethrow_exception(failure);
      return ending;
    }


    /// The stage a checkpoint was written in (0 for a run without stages).
    unsigned int
    stage_of_checkpoint(const std::string &restart)
    {
      const RunState state =
        RunState::read(Checkpoint::locate(restart) + "/state.txt");
      return state.values.count("stage") > 0
               ? static_cast<unsigned int>(state.get("stage"))
               : 0;
    }
  } // namespace


  template <int dim>
  void
  run_scene(ParameterHandler                              &prm,
            MPI_Comm                                       comm,
            const std::string                             &restart,
            const std::function<void(ParameterHandler &)> &read_scene)
  {
    const std::vector<StageParameters> stages = parse_stages(prm);
    if (stages.empty())
      {
        run_one<dim>(prm, comm, restart, {});
        return;
      }
    // Every stage's scene, read (and its values checked) now.
    {
      ParameterHandler scratch;
      read_scene(scratch);
      for (unsigned int k = 0; k < stages.size(); ++k)
        {
          apply_changes(scratch, stages[k]);
          try
            {
              const Simulation<dim> check(scratch,
                                          comm,
                                          "",
                                          {&stages, k, false});
            }
          catch (const InputError &e)
            {
              throw InputError(std::string(e.what()) + " (in the scene of '" +
                               stages[k].path +
                               "', with its changes and those before)");
            }
        }
    }
    const unsigned int first =
      restart.empty() ? 0 : stage_of_checkpoint(restart);
    if (first >= stages.size())
      throw InputError("--restart",
                       restart,
                       "was written in stage " + std::to_string(first) +
                         ", but the scene has " +
                         std::to_string(stages.size()) + " stages");
    for (unsigned int k = 0; k <= first; ++k)
      apply_changes(prm, stages[k]);
    std::string from = restart;
    for (unsigned int k = first; k < stages.size(); ++k)
      {
        if (k > first)
          apply_changes(prm, stages[k]);
        const RunEnding ending =
          run_one<dim>(prm, comm, from, {&stages, k, k > first});
        if (!ending.stage_ended)
          return; // at the end time, within the stage
        from = ending.checkpoint;
      }
  }


  template void
  run_scene<1>(ParameterHandler &,
               MPI_Comm,
               const std::string &,
               const std::function<void(ParameterHandler &)> &);
  template void
  run_scene<2>(ParameterHandler &,
               MPI_Comm,
               const std::string &,
               const std::function<void(ParameterHandler &)> &);
  template void
  run_scene<3>(ParameterHandler &,
               MPI_Comm,
               const std::string &,
               const std::function<void(ParameterHandler &)> &);
} // namespace mpm
