#ifndef mpm_materials_nonlocal_average_h
#define mpm_materials_nonlocal_average_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * The length and weight of a nonlocal average, declared and read in one
   * place for every model option that averages a point value over its
   * neighbours (damage's driving strain, softening's plastic strain).
   */
  struct NonlocalLength
  {
    enum class Weight
    {
      bell,
      gauss
    };

    double length = 0; ///< 0: local
    Weight weight = Weight::bell;

    /// Declare 'nonlocal length' and 'nonlocal weight' in the current
    /// subsection; @p averaged says what is averaged and what for.
    static void
    declare_parameters(ParameterHandler &prm, const std::string &averaged);

    /// Read them from the current subsection; @p path names it in errors.
    void
    parse(const ParameterHandler &prm, const std::string &path);

    bool
    enabled() const
    {
      return length > 0;
    }
  };


  /**
   * The weighted average of a point value over the points of one body
   * within a length of each point,
   *   v_bar_i = sum_j w(|x_i - x_j|) V_j v_j / sum_j w(|x_i - x_j|) V_j,
   * with the bell weight (1 - r^2/l^2)^2 (support l) or the Gaussian
   * exp(-r^2 / (2 l^2)) (cut at 3 l). Near a free surface the weights are
   * renormalised by the denominator.
   *
   * Neighbours are found in bins of the support's size, so a point visits
   * 3^dim bins whatever the ratio of length to cell size. Across MPI
   * ranks, each rank sends to each other rank its points within one
   * support of that rank's points' bounding box: a halo as wide as the
   * support, independent of deal.II's ghost layer, which is one cell deep.
   */
  template <int dim>
  class NonlocalAverage
  {
  public:
    explicit NonlocalAverage(const NonlocalLength &length);

    /**
     * v_bar at the points @p x (this rank's points of the body) with
     * volumes @p volume and values @p value; collective over @p comm.
     * Where it cannot exceed @p floor (no value in reach is above it) the
     * sum is skipped and floor returned: damage only grows where the
     * average exceeds the history kappa, and a body in compression
     * (chi = 0) costs one pass; a plastic strain averages to 0 where no
     * neighbour has yielded.
     */
    std::vector<double>
    average(const std::vector<Point<dim>> &x,
            const std::vector<double>     &volume,
            const std::vector<double>     &value,
            const std::vector<double>     &floor,
            const MPI_Comm                 comm) const;

    /// False for a length of 0 (local: nothing to average).
    bool
    enabled() const
    {
      return length > 0;
    }

    /// The weight at squared distance @p r2 (0 beyond the support).
    double
    weight(const double r2) const;

  private:
    double                 length;
    double                 support;
    NonlocalLength::Weight kind;
  };
} // namespace mpm

#endif
