#ifndef mpm_bodies_extents_h
#define mpm_bodies_extents_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>

#include <mpm/background_grid.h>
#include <mpm/material_points.h>

#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * Where each body reaches, as columns of statistics.csv ('Output/body
   * extents'), for runout and spread:
   * - body<b>_<axis>_min and _max: the box around its points;
   * - body<b>_<axis>_front_min and _front_max: the positions that all but
   *   (100 - p) % of its points stay behind, p the 'front percentile'. The
   *   box follows the one point that went furthest, which a granular
   *   collapse or a landslide can leave far ahead of its deposit (a slope
   *   whose furthest point was at 34.5 m had 99 % of its points within
   *   26.6 m);
   * - with a 'front thickness' T > 0 and gravity along a grid axis, for
   *   each other axis body<b>_<axis>_deposit_min and _max: the furthest
   *   edge of the body where it is at least T thick along gravity. The
   *   thickness of a column of grid cells is the volume of the body's
   *   points in it over the column's cross-section: the depth of its
   *   material with the gaps closed, so that points thrown up above a
   *   thin sheet (a lone point bouncing ahead of a landslide's deposit)
   *   do not make it thick, as the distance from its lowest to its highest
   *   point did (a sheet 0.3 m thick read 2 m). A cohesionless point counts
   *   without the 'opening' its grains gained at zero stress (the volume
   *   its grains hold, V exp(-opening)): a sheet that spread by parting is
   *   thinner than its points' volume says (a collapsed column's front
   *   at 128 cells read 0.885 with it, at its furthest point 0.913; see
   *   tests/deposit_of_parted_grains.prm). A column thick enough
   *   counts with the edge of its outermost point, each point a cube of
   *   its volume. If no column is that thick, the thickest one counts.
   * Positions are the points' (the box and the percentile front), or the
   * edges of their cubes (the deposit). A body without points has an empty
   * box (+inf, -inf) and fronts.
   */
  template <int dim>
  class BodyExtents
  {
  public:
    BodyExtents(const BackgroundGrid<dim> &grid,
                const Tensor<1, dim>      &gravity,
                const double               percentile,
                const double               thickness,
                const unsigned int         n_bodies,
                MPI_Comm                   comm);

    /// The column names, in the order of values().
    std::vector<std::string>
    columns() const;

    /// The columns' values for @p points (collective).
    std::vector<double>
    values(const MaterialPoints<dim> &points) const;

  private:
    /// Where the bins of @p axis start in a body's histograms.
    unsigned int
    bins_before(const unsigned int axis) const;
    /// Per body: lowest x_d and -x_d (one MPI_MIN gives both ends).
    std::vector<double>
    boxes(const MaterialPoints<dim> &points) const;
    /// Per body and axis: the points' histogram along it, counted over all
    /// ranks, in bins of 1 / bins_per_cell of a cell.
    std::vector<double>
    histograms(const MaterialPoints<dim> &points) const;
    /// Per body and column of cells across gravity, over all ranks: its
    /// thickness (the points' volume over its cross-section), and per
    /// other axis the lowest -edge and -(highest +edge) of the points'
    /// cubes.
    struct Columns
    {
      std::vector<double> thickness, edges;
    };
    Columns
    columns_of_cells(const MaterialPoints<dim> &points) const;
    /// The column of cells across gravity that holds @p x.
    unsigned int
    column_of(const Point<dim> &x) const;

    static constexpr unsigned int bins_per_cell = 64;

    const BackgroundGrid<dim> &grid;
    const double               percentile;
    const double               thickness;
    const unsigned int         n_bodies;
    /// The axis gravity acts along (numbers::invalid_unsigned_int if none
    /// or several): the one the deposit's thickness is measured on.
    unsigned int vertical;
    /// The other axes, and the number of cell columns across them.
    std::vector<unsigned int> horizontal;
    unsigned int              n_columns;
    MPI_Comm                  comm;
  };
} // namespace mpm

#endif
