#ifndef mpm_step_context_h
#define mpm_step_context_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <mpm/parameters.h>

#include <sstream>
#include <string>

namespace mpm
{
  using namespace dealii;

  /**
   * What the stages of the step share and none of them owns: the clock
   * (the time at the start of the step and the number of steps taken,
   * which prescribed motions and diagnoses read), the step's first
   * failure, the phases' timer and the communicator. The integrator owns
   * it and advances the clock; each stage holds a reference, so that a
   * stage's constructor names what it works on, not the run around it.
   *
   * A stage that finds the run unstable at one point cannot throw there
   * (the other ranks would wait in the next collective): it keeps its
   * diagnosis with fail(), and the integrator stops the run on all ranks
   * once the stage is done (raise_if_failed()).
   */
  struct StepContext
  {
    StepContext(TimerOutput &timer, const MPI_Comm comm)
      : timer(timer)
      , comm(comm)
    {
    }

    /// "step N, t = T": the moment a diagnosis names.
    std::string
    when() const
    {
      std::ostringstream s;
      s << "step " << n_steps << ", t = " << t;
      return s.str();
    }

    /// Whether a stage of this step has already kept a diagnosis.
    bool
    failed() const
    {
      return !failure.empty();
    }

    /// Keep @p diagnosis as the step's failure, unless an earlier one is
    /// kept: the first is the cause, what follows from it is not.
    void
    fail(const std::string &diagnosis)
    {
      if (failure.empty())
        failure = diagnosis;
    }

    /// Stop the run on all ranks if a stage of any rank kept a diagnosis
    /// (collective).
    void
    raise_if_failed() const
    {
      raise_if_any_failed(failure, comm);
    }

    /// The time at the start of the step, and the steps taken.
    double       t       = 0;
    unsigned int n_steps = 0;
    /// The step's first diagnosis (empty: none).
    std::string    failure;
    TimerOutput   &timer;
    const MPI_Comm comm;
  };
} // namespace mpm

#endif
