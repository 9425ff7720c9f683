#include <mpm/checkpoint.h>
#include <mpm/work_account.h>

namespace mpm
{
  std::array<double, 3>
  WorkAccount::totals(const MPI_Comm comm) const
  {
    return {{Utilities::MPI::sum(external, comm),
             Utilities::MPI::sum(absolute_external, comm),
             Utilities::MPI::sum(absorbed, comm)}};
  }


  void
  WorkAccount::save_state(RunState &state, const MPI_Comm comm) const
  {
    const auto [w, a, s]          = totals(comm);
    state.values["external_work"] = w;
    state.values["absolute_work"] = a;
    state.values["stress_work"]   = s;
  }


  void
  WorkAccount::restore_state(const RunState &state, const MPI_Comm comm)
  {
    external          = state.share_of_rank("external_work", comm);
    absolute_external = state.share_of_rank("absolute_work", comm);
    absorbed          = state.share_of_rank("stress_work", comm);
  }
} // namespace mpm
