#ifndef mpm_background_grid_h
#define mpm_background_grid_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/partitioner.h>
#include <deal.II/base/point.h>
#include <deal.II/base/utilities.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/mapping_cartesian.h>

#include <deal.II/grid/tria.h>

#include <mpm/boundary_conditions/face_kinds.h>
#include <mpm/options.h>

#include <algorithm>
#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace dealii::Particles
{
  template <int dim, int spacedim>
  class ParticleHandler;
}

namespace mpm
{
  using namespace dealii;

  /// The name of grid face @p face (x min, x max, y min, ...), as in its
  /// 'Grid/boundary ...' entry.
  std::string
  face_name(const unsigned int face);


  template <int dim>
  struct GridParameters
  {
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    /// Stop with an InputError naming 'Grid/cells' if the grid cannot fit
    /// in this machine's memory.
    void
    check_grid_fits_in_memory(const std::string &cells_text) const;

    /// Stop with an InputError naming 'Grid/upper corner' if the cells are
    /// too small for the arithmetic (subnormal areas or volumes) or for the
    /// coordinates' precision.
    void
    check_cells_are_resolved(const std::string &upper_corner_text) const;

    Point<dim>                        lower_corner;
    Point<dim>                        upper_corner;
    std::array<unsigned int, dim>     n_cells;
    std::array<BoundaryType, 2 * dim> boundary; ///< x-, x+, y-, y+, z-, z+
    double friction_coefficient; ///< Coulomb mu of the friction faces
    /// The body whose material sets the absorbing faces' impedances.
    unsigned int absorbing_body;
    /// Grid cells per tile edge (a deal.II cell is a tile of T^dim grid
    /// cells): a power of two that divides the cells in every direction.
    unsigned int tile_size;
    /// Largest imbalance of work between ranks (max / mean - 1) before the
    /// grid is repartitioned during the run; 0: never.
    double imbalance_limit;

    /// Size of a cell in each direction.
    Tensor<1, dim>
    cell_size() const;

    /// Lexicographic index of the cell that holds @p x (and @p x's
    /// coordinates in it), or numbers::invalid_unsigned_int outside.
    unsigned int
    locate(const Point<dim> &x, Point<dim> &reference) const;

    /**
     * A point found less than a quarter of a cell behind a closed face
     * (fixed, slip or friction) is put back on the face and its velocity
     * out through it removed: the face holds the nodes, not the points,
     * and a point on a no-slip floor under material that presses down
     * takes a share of the downward velocity of the nodes above it, so it
     * can cross the face by round-off or a small fraction of a step's
     * motion. True if @p x was put back (and @p velocity changed); false if
     * it is inside, or further out, or behind a face that lets it leave.
     */
    bool
    put_back_behind_closed_face(Point<dim> &x, Tensor<1, dim> &velocity) const;
  };


  /// The formula behind GridParameters::locate() and BackgroundGrid::locate():
  /// the Cartesian indices of the cell holding @p x and @p x's coordinates
  /// in it, with the inverse cell size given (the hot path caches it);
  /// false outside the grid.
  template <int dim>
  inline bool
  locate_in_lattice(const Point<dim>                    &x,
                    const Point<dim>                    &lower_corner,
                    const Tensor<1, dim>                &inverse_cell_size,
                    const std::array<unsigned int, dim> &n_cells,
                    std::array<unsigned int, dim>       &cell,
                    Point<dim>                          &reference)
  {
    for (unsigned int d = 0; d < dim; ++d)
      {
        const double s = (x[d] - lower_corner[d]) * inverse_cell_size[d];
        // The negated comparison also sends NaN to 'outside'.
        if (!(s >= 0.) || !(s < n_cells[d]))
          return false;
        cell[d]      = static_cast<unsigned int>(s);
        reference[d] = s - cell[d];
      }
    return true;
  }


  /// The lexicographic index of the cell with Cartesian indices @p cell.
  template <int dim>
  inline unsigned int
  lexicographic_index(const std::array<unsigned int, dim> &cell,
                      const std::array<unsigned int, dim> &n_cells)
  {
    unsigned int index = 0;
    for (int d = dim - 1; d >= 0; --d)
      index = index * n_cells[d] + cell[d];
    return index;
  }


  /**
   * The background grid: an axis-aligned box of equal cells. Because it is
   * Cartesian, the cell holding a point, the point's reference coordinates
   * and the nodes it touches follow from its position in a few flops; the
   * tables built here turn those into deal.II cells and nodal-vector
   * indices without any search.
   *
   * deal.II does not see the grid's cells one by one: its cells are
   * *tiles* of T^dim grid cells (T = GridParameters::tile_size()), and an
   * FE_Q(T) with equidistant support points puts its DoFs on the grid's
   * nodes, so that the DoFHandler numbers and partitions the nodes as
   * before. A deal.II cell with its DoFs costs about 500 bytes in 2D, more
   * than a material point; with T = 4 that is 30-40 bytes per grid cell.
   * The tiles are the cells of a coarse mesh refined globally, so p4est
   * keeps on each rank only its part of the refined mesh, and memory falls
   * with the number of ranks. deal.II's particle handler stores the points
   * by tile; a point moves in deal.II only when it changes tile.
   *
   * Nodal quantities live in LinearAlgebra::distributed::Vector objects
   * that interleave several components per node (node-major), so one
   * compress() or update_ghost_values() moves all of them at once.
   */
  template <int dim>
  class BackgroundGrid
  {
  public:
    static constexpr unsigned int invalid = numbers::invalid_unsigned_int;
    using CellCoordinates                 = std::array<unsigned int, dim>;

    /// @p work_estimate, if given, says how much work a grid cell (given
    /// by its lower corner) will carry; the distributed grid is then
    /// partitioned so that every rank gets the same work rather than the
    /// same number of cells (material points usually fill only part of
    /// the grid). @p restart_file: load the partition (and the points
    /// attached to it) from a checkpoint instead of partitioning by
    /// @p work_estimate.
    BackgroundGrid(
      const GridParameters<dim>                             &parameters,
      MPI_Comm                                               comm,
      const std::function<unsigned int(const Point<dim> &)> &work_estimate = {},
      const std::string                                     &restart_file = "");

    const Triangulation<dim> &
    triangulation() const
    {
      return *tria;
    }
    const Mapping<dim> &
    mapping() const
    {
      return cartesian_mapping;
    }
    const DoFHandler<dim> &
    dof_handler() const
    {
      return dofs;
    }
    const GridParameters<dim> &
    parameters() const
    {
      return prm;
    }

    /// Cell size in each direction, and its inverse.
    const Tensor<1, dim> &
    cell_size() const
    {
      return h;
    }
    const Tensor<1, dim> &
    inverse_cell_size() const
    {
      return inv_h;
    }
    double
    min_cell_size() const;
    /// Number of grid cells (all ranks).
    types::global_cell_index
    n_cells() const;

    /// Lexicographic index of the cell that holds @p x, or invalid if @p x
    /// lies outside the grid. @p reference receives x in the cell's
    /// reference coordinates [0,1]^dim.
    unsigned int
    locate(const Point<dim> &x, Point<dim> &reference) const;

    /// The same, as the cell's Cartesian indices (i, j, k); false outside.
    bool
    locate(const Point<dim> &x,
           CellCoordinates  &cell,
           Point<dim>       &reference) const
    {
      return locate_in_lattice<dim>(
        x, prm.lower_corner, inv_h, prm.n_cells, cell, reference);
    }

    /// Cells per tile edge (T).
    unsigned int
    tile_size() const
    {
      return T;
    }

    /// Lexicographic index of the tile that holds the grid cell @p cell.
    unsigned int
    tile_of(const CellCoordinates &cell) const
    {
      unsigned int index = 0;
      for (int d = dim - 1; d >= 0; --d)
        index = index * n_tiles[d] + (cell[d] >> log2_T);
      return index;
    }

    /// The deal.II cell of the tile with lexicographic index @p index (an
    /// owned or ghost tile).
    const typename Triangulation<dim>::active_cell_iterator &
    tile(const unsigned int index) const
    {
      return tiles[index];
    }

    /// Lexicographic index of the tile a deal.II cell (of the finest
    /// level) is: the one that holds its centre.
    unsigned int
    tile_of(const typename Triangulation<dim>::cell_iterator &cell) const
    {
      CellCoordinates c{};
      Point<dim>      xi;
      const bool      inside = locate(cell->center(), c, xi);
      (void)inside;
      Assert(inside, ExcInternalError());
      return tile_of(c);
    }

    /// Lexicographic indices of the locally owned tiles, in deal.II's
    /// order of its cells, which is the order of the points' data.
    const std::vector<unsigned int> &
    locally_owned_tiles() const
    {
      return owned_tiles;
    }

    /// Cartesian indices of the lower corner cell of tile @p index.
    CellCoordinates
    first_cell_of_tile(unsigned int index) const
    {
      CellCoordinates c;
      for (unsigned int d = 0; d < dim; ++d)
        {
          c[d] = (index % n_tiles[d]) << log2_T;
          index /= n_tiles[d];
        }
      return c;
    }

    /// Call @p f(cell, lower corner) for every grid cell of tile @p index,
    /// lexicographically.
    template <typename Function>
    void
    for_each_cell_of_tile(const unsigned int index, const Function &f) const
    {
      const CellCoordinates first = first_cell_of_tile(index);
      for (unsigned int k = 0; k < Utilities::pow(T, dim); ++k)
        {
          const CellCoordinates c = lattice_point(first, k, T);
          Point<dim>            corner;
          for (unsigned int d = 0; d < dim; ++d)
            corner[d] = prm.lower_corner[d] + c[d] * h[d];
          f(c, corner);
        }
    }

    /// The reference coordinates in its tile of a point in grid cell
    /// @p cell at reference coordinates @p xi (what deal.II stores).
    Point<dim>
    tile_reference(const CellCoordinates &cell, const Point<dim> &xi) const
    {
      Point<dim> r;
      for (unsigned int d = 0; d < dim; ++d)
        r[d] = ((cell[d] & (T - 1)) + xi[d]) / T;
      return r;
    }

    /// The inverse of tile_reference(): the grid cell and the reference
    /// coordinates in it of a point at @p reference in the tile whose
    /// first cell is @p first. (Exact for T = 1; for larger T the point's
    /// coordinates keep all but the last two or three bits.)
    void
    cell_in_tile(const CellCoordinates &first,
                 const Point<dim>      &reference,
                 CellCoordinates       &cell,
                 Point<dim>            &xi) const
    {
      for (unsigned int d = 0; d < dim; ++d)
        {
          const double       s = reference[d] * T;
          const unsigned int k = std::min(static_cast<unsigned int>(s), T - 1);
          cell[d]              = first[d] + k;
          xi[d]                = s - k;
        }
    }

    /**
     * Local index (into a scalar layout) of the node with Cartesian
     * indices @p node, for a node of the stencil of a point in grid cell
     * @p cell of an owned tile: the stencils of all bases reach at most one
     * node beyond the nodes of the point's cell, so each owned tile keeps
     * the local indices of its nodes and one more layer around them (its
     * node block). Nodes beyond the grid give invalid.
     */
    unsigned int
    local_node(const CellCoordinates &cell, const CellCoordinates &node) const
    {
      const unsigned int tile = tile_of(cell);
      return node_block(
        tile)[node_block_offset(first_cell_of_tile(tile), node)];
    }

    /// The node block of owned tile @p tile: (T+3)^dim local indices,
    /// lexicographic, from the node before the tile's first in every
    /// direction (see node_block_offset()).
    const unsigned int *
    node_block(const unsigned int tile) const
    {
      Assert(first_block_entry[tile] != invalid,
             ExcMessage("node blocks are kept for owned tiles only"));
      return node_blocks.data() + first_block_entry[tile];
    }

    /// Where the node @p node lies in the node block of the tile whose first
    /// cell is @p first.
    unsigned int
    node_block_offset(const CellCoordinates &first,
                      const CellCoordinates &node) const
    {
      unsigned int offset = 0;
      for (int d = dim - 1; d >= 0; --d)
        offset = offset * (T + 3) + (node[d] + 1 - first[d]);
      return offset;
    }

    /// Cartesian indices of the owned node with local index @p i.
    CellCoordinates
    owned_node_coordinates(const unsigned int i) const
    {
      return owned_node_lattice[i];
    }

    /// The integral of the linear hat function of owned node @p i: a share
    /// 1/2^dim of each cell around it (less at the grid's faces).
    double
    node_support_volume(const unsigned int i) const;

    /// The nodes' partitioner: local node index <-> global DoF index of
    /// the FE_Q(T) DoFHandler (owned nodes, then the ghost nodes that
    /// stencils of this rank's points reach).
    const Utilities::MPI::Partitioner &
    node_partitioner() const
    {
      return *scalar_partitioner;
    }
    /// Partitioner for @p n_components interleaved values per node.
    std::shared_ptr<const Utilities::MPI::Partitioner>
    make_partitioner(const unsigned int n_components) const;

    unsigned int
    n_locally_owned_nodes() const
    {
      return n_owned_nodes;
    }

    /// Local indices of the owned nodes in the box [lower, upper].
    std::vector<unsigned int>
    owned_nodes_in_box(const Point<dim> &lower, const Point<dim> &upper) const;

    /// True if the box [lower, upper] lies inside the grid.
    bool
    contains(const Point<dim> &lower, const Point<dim> &upper) const;

    /// After a restart's points are unpacked: partition the grid by the
    /// work estimate again (the points move with their cells) and rebuild
    /// the nodes. A checkpoint loads with a uniform partition.
    void
    restore_partition(Particles::ParticleHandler<dim, dim> &particles);

    /// This rank's work per step: its tiles' nodes and, at 30 times the
    /// cost of a node, the points they hold (the weight of the partition).
    double
    local_work(const Particles::ParticleHandler<dim, dim> &particles) const;

    /// Partition the grid by the points each tile holds now (the points
    /// move with their tiles) and rebuild the nodes. Everything that holds
    /// nodal data or node indices must be set up again afterwards.
    void
    repartition(Particles::ParticleHandler<dim, dim> &particles);

  private:
    /// The @p k-th point, lexicographically, of a block of @p width^dim
    /// lattice points whose first is @p first: the cells of a tile, its
    /// nodes, its node block.
    static CellCoordinates
    lattice_point(const CellCoordinates &first,
                  unsigned int           k,
                  const unsigned int     width)
    {
      CellCoordinates c;
      for (unsigned int d = 0; d < dim; ++d, k /= width)
        c[d] = first[d] + k % width;
      return c;
    }

    /// True if the grid is partitioned by a work estimate: there is one,
    /// and more than one rank.
    bool
    partitions_by_work() const;
    /// Partition the distributed grid by the work estimate (if
    /// partitions_by_work()).
    void
    partition_by_work();
    /// Repartition the distributed grid with the weight of each tile given
    /// by @p points_in_tile (the points it holds or will hold).
    void
    partition_by_points(
      const std::function<unsigned int(
        const typename Triangulation<dim>::cell_iterator &)> &points_in_tile);
    /// Number the nodes and build every table that depends on the
    /// partition.
    void
    distribute_nodes();
    /// The owned and ghost tiles, and the nodes of each in lexicographic
    /// order (global DoF indices until distribute_nodes() makes them
    /// local).
    void
    build_tile_tables(std::vector<types::global_dof_index> &global_nodes);
    /// The owned nodes and the ghost nodes that stencils from owned tiles
    /// reach.
    IndexSet
    relevant_nodes(
      const std::vector<types::global_dof_index> &global_nodes) const;
    /// The node blocks of the owned tiles, from tile_nodes (which they
    /// replace).
    void
    build_node_blocks();

    const GridParameters<dim>                       prm;
    MPI_Comm                                        comm;
    std::function<unsigned int(const Point<dim> &)> work_estimate;
    const unsigned int                              T;
    const unsigned int                              log2_T;
    CellCoordinates                                 n_tiles;
    std::unique_ptr<Triangulation<dim>>             tria;
    MappingCartesian<dim>                           cartesian_mapping;
    FE_Q<dim>                                       fe;
    DoFHandler<dim>                                 dofs;
    Tensor<1, dim>                                  h;
    Tensor<1, dim>                                  inv_h;

    std::shared_ptr<const Utilities::MPI::Partitioner> scalar_partitioner;
    unsigned int                                       n_owned_nodes;

    /// Per tile (all of the grid's): its deal.II cell if owned or ghost,
    /// and where its (T+1)^dim nodes start in tile_nodes (or invalid;
    /// tile_nodes is emptied once the node blocks are built).
    std::vector<typename Triangulation<dim>::active_cell_iterator> tiles;
    std::vector<unsigned int> first_node_entry;
    std::vector<unsigned int> tile_nodes;
    /// Per tile: where its node block starts in node_blocks (owned tiles;
    /// invalid for the others).
    std::vector<unsigned int>    first_block_entry;
    std::vector<unsigned int>    node_blocks;
    std::vector<unsigned int>    owned_tiles;
    std::vector<CellCoordinates> owned_node_lattice;
  };
} // namespace mpm

#endif
