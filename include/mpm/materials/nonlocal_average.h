#ifndef mpm_materials_nonlocal_average_h
#define mpm_materials_nonlocal_average_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>

#include <mpm/materials/damage.h>

#include <vector>

namespace mpm
{
  using namespace dealii;

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
    explicit NonlocalAverage(const DamageLaw &law);

    /**
     * v_bar at the points @p x (this rank's points of the body) with
     * volumes @p volume and values @p value; collective over @p comm.
     * Where it cannot exceed @p floor (no value in reach is above it) the
     * sum is skipped and floor returned: damage only grows where the
     * average exceeds the history kappa, and a body in compression
     * (chi = 0) costs one pass.
     */
    std::vector<double>
    average(const std::vector<Point<dim>> &x,
            const std::vector<double>     &volume,
            const std::vector<double>     &value,
            const std::vector<double>     &floor,
            const MPI_Comm                 comm) const;

    /// The weight at squared distance @p r2 (0 beyond the support).
    double
    weight(const double r2) const;

  private:
    double            length;
    double            support;
    DamageLaw::Weight kind;
  };
} // namespace mpm

#endif
