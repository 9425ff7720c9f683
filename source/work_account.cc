#include <mpm/checkpoint.h>
#include <mpm/work_account.h>

#include <array>
#include <utility>
#include <vector>

namespace mpm
{
  namespace
  {
    /// Each sum with its key in a checkpoint's state.txt. The grid's
    /// work (the last four) was not accounted by older
    /// checkpoints: missing there, it starts from 0.
    template <typename Account>
    auto
    keyed_sums(Account &a)
    {
      using Sum = decltype(&a.external);
      return std::array<std::pair<const char *, Sum>, 7>{
        {{"external_work", &a.external},
         {"absolute_work", &a.absolute_external},
         {"stress_work", &a.absorbed},
         {"face_friction_work", &a.face_friction},
         {"face_constraint_work", &a.face_constraint},
         {"damping_work", &a.damping},
         {"contact_work", &a.contact}}};
    }
    constexpr unsigned int n_required_sums = 3;
  } // namespace


  WorkAccount
  WorkAccount::totals(const MPI_Comm comm) const
  {
    WorkAccount         total;
    const auto          mine = keyed_sums(*this);
    const auto          sums = keyed_sums(total);
    std::vector<double> values;
    for (const auto &[key, sum] : mine)
      values.push_back(*sum);
    // One reduction for all the sums.
    MPI_Allreduce(
      MPI_IN_PLACE, values.data(), values.size(), MPI_DOUBLE, MPI_SUM, comm);
    for (unsigned int i = 0; i < sums.size(); ++i)
      *sums[i].second = values[i];
    return total;
  }


  void
  WorkAccount::save_state(RunState &state, const MPI_Comm comm) const
  {
    WorkAccount total = totals(comm);
    for (const auto &[key, sum] : keyed_sums(total))
      state.values[key] = *sum;
  }


  void
  WorkAccount::restore_state(const RunState &state, const MPI_Comm comm)
  {
    const auto sums = keyed_sums(*this);
    for (unsigned int i = 0; i < sums.size(); ++i)
      *sums[i].second =
        i < n_required_sums || state.values.count(sums[i].first) != 0
          ? state.share_of_rank(sums[i].first, comm)
          : 0.;
  }
} // namespace mpm
