#ifndef mpm_transfer_f_bar_h
#define mpm_transfer_f_bar_h

#include <mpm/background_grid.h>
#include <mpm/material_points.h>

#include <array>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * F-bar (`Simulation/F-bar`): the volumetric part of the strain rate and
   * of the stress averaged over each grid cell, per body, as a pair.
   *
   * - The stress update sees each point's step with the volume change of
   *   its cell: average_volume_change() (see there).
   * - The internal force sees each point's stress with the mean stress of
   *   its cell: average_mean_stress(). The force is then the adjoint of the
   *   averaged strain rate, so that the work the grid does on the points
   *   is the work their stresses absorb; with the point's own mean stress
   *   it is not where the mean stress varies within a cell (see there).
   *
   * Both bin the points by the cell the last relocation put them in: in a
   * step, the transfer to the grid and the kinematics see the same bins.
   */
  template <int dim>
  class FBar
  {
  public:
    FBar(const BackgroundGrid<dim> &grid, MaterialPoints<dim> &points);

    /// Replace each point's volume change over the step @p dt (its strain
    /// rate L, volume and F, after the kinematics) by that of its cell.
    void
    average_volume_change(const double dt);

    /// Store in each point the difference between its cell's mean stress
    /// and its own (FieldLayout::mean_stress_correction), for the force.
    void
    average_mean_stress();

  private:
    /**
     * Tile by tile: call @p add(q, sums) for every point of a deformable
     * body with the two sums of its (cell, body) bin, which returns the
     * point's own value (computed once), then @p apply(q, sums, own,
     * shared) with the bin's totals, that value and whether the point
     * shares its cell with others (a point alone keeps its own values).
     */
    template <typename Add, typename Apply>
    void
    for_each_cell_bin(const Add &add, const Apply &apply);

    const BackgroundGrid<dim> &grid;
    MaterialPoints<dim>       &points;
    /// Each body's reference density, 0 for a rigid body (not averaged).
    std::vector<double> density_of_body;
    /// Per body: average the step's volume change (its material's volume
    /// has a history), or J itself.
    std::vector<bool> by_increment;
    /// Scratch of for_each_cell_bin, kept between calls.
    std::vector<std::array<double, 2>> sums;
    std::vector<unsigned int>          n_in_cell;
    struct BinnedPoint
    {
      double      *q;
      unsigned int bin;
      double       own; ///< what add() returned for it
    };
    std::vector<BinnedPoint> deformable;
  };
} // namespace mpm

#endif
