#ifndef mpm_boundary_conditions_reaction_meter_h
#define mpm_boundary_conditions_reaction_meter_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>

#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * A condition that reports the mean force it exerts over each output
   * interval as columns of statistics.csv (the velocity region, each rigid
   * wall, the virtual fluid, the rigid bodies of contact). Simulation keeps
   * one list of them, from which the columns' names, their values and
   * their restart all come.
   */
  class ForceReporter
  {
  public:
    virtual ~ForceReporter() = default;

    /// The statistics columns (none when the scene has nothing to report).
    virtual std::vector<std::string>
    columns() const = 0;

    /// The mean forces since the last call, in the order of columns(),
    /// summed over the ranks (collective); the averaging restarts.
    virtual std::vector<double>
    mean_force_since_last_call(const double time, MPI_Comm comm) = 0;
  };


  /**
   * The mean force of a boundary condition over an output interval: the
   * impulses it gives are summed, and read as impulse / elapsed time.
   * Explicit MPM's nodal or contact reactions are noisy from step to step;
   * their mean over an interval is what a load cell would show.
   */
  template <int dim>
  class ReactionMeter
  {
  public:
    /// Statistics columns "<prefix>_x", ...
    static std::vector<std::string>
    columns(const std::string &prefix)
    {
      std::vector<std::string> c;
      for (unsigned int d = 0; d < dim; ++d)
        c.push_back(prefix + "_" + "xyz"[d]);
      return c;
    }

    void
    add(const Tensor<1, dim> &impulse)
    {
      sum += impulse;
    }

    /// The mean force since the last call, summed over the ranks of
    /// @p comm (collective), and restart.
    std::vector<double>
    mean_since_last_call(const double time, MPI_Comm comm)
    {
      const Tensor<1, dim> total = Utilities::MPI::sum(sum, comm);
      std::vector<double>  force;
      for (unsigned int d = 0; d < dim; ++d)
        force.push_back(time > last_time ? total[d] / (time - last_time) : 0.);
      sum       = Tensor<1, dim>();
      last_time = time;
      return force;
    }

  private:
    Tensor<1, dim> sum;
    double         last_time = 0;
  };


  /**
   * A condition with one ReactionMeter (the velocity region, each rigid
   * wall, the virtual fluid): its columns "<prefix>_x", ... and their
   * values, written once here for all of them. An empty prefix: the
   * condition does not act in this scene and reports nothing.
   */
  template <int dim>
  class MeteredReporter : public ForceReporter
  {
  public:
    explicit MeteredReporter(const std::string &column_prefix)
      : prefix(column_prefix)
    {
    }

    std::vector<std::string>
    columns() const override
    {
      return prefix.empty() ? std::vector<std::string>()
                            : ReactionMeter<dim>::columns(prefix);
    }

    std::vector<double>
    mean_force_since_last_call(const double time, MPI_Comm comm) override
    {
      if (prefix.empty())
        return {};
      return meter.mean_since_last_call(time, comm);
    }

    /// Count @p impulse, given to the material by the condition (this
    /// rank's share), in its force.
    void
    add_impulse(const Tensor<1, dim> &impulse)
    {
      meter.add(impulse);
    }

  private:
    const std::string  prefix;
    ReactionMeter<dim> meter;
  };
} // namespace mpm

#endif
