#ifndef mpm_work_account_h
#define mpm_work_account_h

#include <deal.II/base/mpi.h>

#include <array>

namespace mpm
{
  struct RunState;

  /**
   * The running sums of the energy balance (see EnergyGuard), kept in one
   * place: the work done on the bodies from outside (ExternalLoads closes
   * each step's into it), the sum of that work's absolute step increments,
   * and the work the bodies' stresses absorbed (StressUpdate, with
   * 'Simulation/energy residual'). Each rank holds its share; the totals
   * are sums over the ranks. A checkpoint keeps the totals, and a restart,
   * which may run on another number of ranks, gives them to the first.
   */
  struct WorkAccount
  {
    double external          = 0;
    double absolute_external = 0;
    double absorbed          = 0;

    /// {external, absolute_external, absorbed} summed over the ranks
    /// (collective).
    std::array<double, 3>
    totals(const MPI_Comm comm) const;

    /// Put the totals into @p state (collective), or take them back.
    void
    save_state(RunState &state, const MPI_Comm comm) const;
    void
    restore_state(const RunState &state, const MPI_Comm comm);
  };
} // namespace mpm

#endif
