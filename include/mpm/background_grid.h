#ifndef mpm_background_grid_h
#define mpm_background_grid_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/partitioner.h>
#include <deal.II/base/point.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/mapping_cartesian.h>

#include <deal.II/grid/tria.h>

#include <array>
#include <functional>
#include <memory>
#include <vector>

namespace dealii::Particles
{
  template <int dim, int spacedim>
  class ParticleHandler;
}

namespace mpm
{
  using namespace dealii;

  /// What a grid face does to the nodal velocity.
  enum class BoundaryType
  {
    free,     ///< nothing
    fixed,    ///< all velocity components zero
    slip,     ///< normal velocity component zero
    friction, ///< Coulomb contact: no penetration, free separation
    absorbing ///< viscous dashpots that let waves leave (Lysmer-Kuhlemeyer)
  };


  /// A node on an absorbing face: the face (x min, x max, y min, ...) and
  /// the share of its area the node's dashpots act on.
  struct AbsorbingNode
  {
    unsigned int node, face;
    double       area;
  };

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

    Point<dim>                        lower_corner;
    Point<dim>                        upper_corner;
    std::array<unsigned int, dim>     n_cells;
    std::array<BoundaryType, 2 * dim> boundary; ///< x-, x+, y-, y+, z-, z+
    double friction_coefficient; ///< Coulomb mu of the friction faces
    /// The body whose material sets the absorbing faces' impedances.
    unsigned int absorbing_body;

    /// Size of a cell in each direction.
    Tensor<1, dim>
    cell_size() const;

    /// Lexicographic index of the cell that holds @p x (and @p x's
    /// coordinates in it), or numbers::invalid_unsigned_int outside.
    unsigned int
    locate(const Point<dim> &x, Point<dim> &reference) const;
  };


  /// The formula behind GridParameters::locate() and BackgroundGrid::locate(),
  /// with the inverse cell size given (the hot path caches it).
  template <int dim>
  inline unsigned int
  locate_in_lattice(const Point<dim>                    &x,
                    const Point<dim>                    &lower_corner,
                    const Tensor<1, dim>                &inverse_cell_size,
                    const std::array<unsigned int, dim> &n_cells,
                    Point<dim>                          &reference)
  {
    unsigned int index  = 0;
    unsigned int stride = 1;
    for (unsigned int d = 0; d < dim; ++d)
      {
        const double s = (x[d] - lower_corner[d]) * inverse_cell_size[d];
        // The negated comparison also sends NaN to 'outside'.
        if (!(s >= 0.) || !(s < n_cells[d]))
          return numbers::invalid_unsigned_int;
        const unsigned int i = static_cast<unsigned int>(s);
        reference[d]         = s - i;
        index += i * stride;
        stride *= n_cells[d];
      }
    return index;
  }


  /**
   * The background grid: an axis-aligned box of equal cells. Because it is
   * Cartesian, the cell holding a point, the point's reference coordinates
   * and the nodes it touches follow from its position in a few flops; the
   * tables built here turn those into deal.II cells and nodal-vector
   * indices without any search.
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

    /// @p work_estimate, if given, says how much work a cell (given by its
    /// lower corner) will carry; the distributed grid is then partitioned
    /// so that every rank gets the same work rather than the same number
    /// of cells (material points usually fill only part of the grid).
    /// @p restart_file: load the partition (and the points attached to
    /// it) from a checkpoint instead of partitioning by @p work_estimate.
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

    /// Lexicographic index of the cell that holds @p x, or invalid if @p x
    /// lies outside the grid. @p reference receives x in the cell's
    /// reference coordinates [0,1]^dim.
    unsigned int
    locate(const Point<dim> &x, Point<dim> &reference) const;

    /// The deal.II cell with lexicographic index @p index.
    const typename Triangulation<dim>::active_cell_iterator &
    cell(const unsigned int index) const
    {
      return cells[index];
    }

    /// Lexicographic index of a deal.II cell.
    unsigned int
    cartesian_index(
      const typename Triangulation<dim>::active_cell_iterator &cell) const
    {
      return cartesian_index_of_active_cell[cell->active_cell_index()];
    }

    /// Lexicographic indices of the locally owned cells.
    const std::vector<unsigned int> &
    locally_owned_cells() const
    {
      return owned_cells;
    }

    /// Cartesian indices (i, j, k) of the cell with lexicographic index
    /// @p index.
    std::array<unsigned int, dim>
    cell_coordinates(unsigned int index) const
    {
      std::array<unsigned int, dim> c;
      for (unsigned int d = 0; d < dim; ++d)
        {
          c[d] = index % prm.n_cells[d];
          index /= prm.n_cells[d];
        }
      return c;
    }

    /// Local index (into a scalar layout) of the node with lexicographic
    /// index @p cartesian_node, for every node of the locally owned and
    /// ghost cells: the stencils of all bases stay within them, because a
    /// point's nodes belong to its cell or to the cells next to it.
    /// Other nodes give invalid.
    unsigned int
    local_node(const unsigned int cartesian_node) const
    {
      return local_node_of_cartesian[cartesian_node];
    }

    /// The nodes' partitioner: local node index <-> global DoF index of
    /// the FE_Q(1) DoFHandler (owned, then ghost nodes).
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

    /// Owned nodes with boundary constraints and the bit mask of the
    /// velocity components they hold at zero.
    const std::vector<std::pair<unsigned int, unsigned int>> &
    constrained_nodes() const
    {
      return node_constraints;
    }

    /// Owned nodes on friction faces and the bit mask of those faces
    /// (bit f: face f = x min, x max, y min, ...).
    const std::vector<std::pair<unsigned int, unsigned int>> &
    friction_nodes() const
    {
      return node_frictions;
    }

    /// Owned nodes on absorbing faces, one entry per node and face.
    const std::vector<AbsorbingNode> &
    absorbing_nodes() const
    {
      return node_dashpots;
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

  private:
    /// True if the grid is partitioned by a work estimate: there is one,
    /// and more than one rank.
    bool
    partitions_by_work() const;
    /// Partition the distributed grid by the work estimate (if
    /// partitions_by_work()).
    void
    partition_by_work();
    /// Number the nodes and build every table that depends on the
    /// partition.
    void
    distribute_nodes();
    void
    build_cell_tables();
    void
    build_node_constraints();

    const GridParameters<dim>                       prm;
    MPI_Comm                                        comm;
    std::function<unsigned int(const Point<dim> &)> work_estimate;
    std::unique_ptr<Triangulation<dim>>             tria;
    MappingCartesian<dim>                           cartesian_mapping;
    FE_Q<dim>                                       fe;
    DoFHandler<dim>                                 dofs;
    Tensor<1, dim>                                  h;
    Tensor<1, dim>                                  inv_h;

    std::shared_ptr<const Utilities::MPI::Partitioner> scalar_partitioner;
    unsigned int                                       n_owned_nodes;

    std::vector<typename Triangulation<dim>::active_cell_iterator> cells;
    std::vector<unsigned int> cartesian_index_of_active_cell;
    std::vector<unsigned int> owned_cells;
    std::vector<unsigned int> local_node_of_cartesian;
    std::vector<std::pair<unsigned int, unsigned int>> node_constraints;
    std::vector<std::pair<unsigned int, unsigned int>> node_frictions;
    std::vector<AbsorbingNode>                         node_dashpots;
  };
} // namespace mpm

#endif
