#ifndef mpm_transfer_point_loop_h
#define mpm_transfer_point_loop_h

// The one particle loop of the step: every stage that visits the points
// with their stencils (the transfers, the macro step) goes through
// PointLoop::for_each_point, a template on the basis and the kernel, so
// that each loop is compiled with its kernel inlined and no virtual call.
#include <mpm/background_grid.h>
#include <mpm/basis.h>
#include <mpm/field_layout.h>
#include <mpm/material_points.h>
#include <mpm/parameters.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /// The length of the local array of a nodal vector: owned and ghost
  /// entries (loops that clear or copy all of them).
  inline unsigned int
  n_local_entries(const LinearAlgebra::distributed::Vector<double> &v)
  {
    return v.locally_owned_size() + v.get_partitioner()->n_ghost_indices();
  }


  /**
   * The scene's basis on the grid and the loop over the points with their
   * stencils in it.
   */
  template <int dim>
  class PointLoop
  {
  public:
    PointLoop(const BackgroundGrid<dim> &grid,
              MaterialPoints<dim>       &points,
              const BasisType            basis_type)
      : grid(grid)
      , points(points)
      , basis_type(basis_type)
    {
      // uGIMP/cpGIMP: a point's domain is h / (points per cell) wide.
      for (const auto &body : points.bodies())
        initial_half_width_of_body.push_back(0.5 / body.particles_per_cell);
      // The cubic B-spline's stencil spans two cells on each side of a
      // point's node; the boundary folding needs a second grid node inside.
      if (basis_type == BasisType::cubic_bspline)
        for (unsigned int d = 0; d < dim; ++d)
          if (grid.parameters().n_cells[d] < 2)
            throw InputError("Simulation/basis",
                             "cubic B-spline",
                             "needs at least 2 grid cells in every direction "
                             "('Grid/cells')");
    }

    /// Call @p f with the scene's basis on this grid (the basis class is
    /// chosen at run time, once, and everything in @p f is compiled for
    /// it).
    template <typename F>
    void
    with_scene_basis(const F &f) const
    {
      with_basis<dim>(basis_type, [&](auto *tag) {
        using Basis = std::remove_pointer_t<decltype(tag)>;
        f(Basis(grid.parameters().n_cells, grid.cell_size()));
      });
    }

    /**
     * Visit every locally owned point tile by tile with its stencil: the
     * nodes it touches (as local indices of the nodal vectors), the basis
     * weights and gradients at its position. Every particle loop of the step
     * goes through here, so the stencil is evaluated the same way everywhere.
     * The point's cell and its reference coordinates there come from its
     * reference location in the tile, set by the last relocation: all loops
     * of a step see the points where the step began (MUSL's second transfer
     * to the grid uses the step's first stencils), even after the gather
     * has moved them.
     */
    template <typename Basis, typename Kernel>
    void
    for_each_point(const Basis &basis, const Kernel &kernel) const
    {
      typename Basis::Stencil s;
      Tensor<1, dim>          half_width;
      // The node lists of the patterns seen so far in the current cell: the
      // lookup of nodal-vector indices is done once per cell and pattern
      // (the points of a cell are mostly stored together).
      std::array<std::array<unsigned int, Basis::n_nodes>, Basis::n_patterns>
                                       pattern_nodes;
      Particles::ParticleHandler<dim> &particles = points.handler();
      typename BackgroundGrid<dim>::CellCoordinates cell, last_cell, first;
      // The stencil's nodes are looked up in the tile's node block (the
      // tile's nodes and one layer around them): one load per node.
      const unsigned int *block = nullptr;
      const auto index_of = [&](const std::array<unsigned int, dim> &node) {
        const unsigned int i = block[grid.node_block_offset(first, node)];
        // Every stencil node must be owned or a ghost here (see
        // BackgroundGrid::local_node); Debug builds check it.
        Assert(i != BackgroundGrid<dim>::invalid,
               ExcMessage("a stencil node is not known on this rank"));
        return i;
      };
      unsigned int known_patterns = 0;
      last_cell.fill(BackgroundGrid<dim>::invalid);
      for (const unsigned int index : grid.locally_owned_tiles())
        {
          const auto        &tile = grid.tile(index);
          const unsigned int n    = particles.n_particles_in_cell(tile);
          if (n == 0)
            continue;
          first  = grid.first_cell_of_tile(index);
          block  = grid.node_block(index);
          auto p = particles.particles_in_cell(tile).begin();
          for (unsigned int i = 0; i < n; ++i, ++p)
            {
              Point<dim> xi;
              grid.cell_in_tile(first, p->get_reference_location(), cell, xi);
              if (cell != last_cell)
                {
                  known_patterns = 0;
                  last_cell      = cell;
                }
              double *q = p->get_properties().data();
              if constexpr (Basis::needs_half_width)
                half_width = domain_half_width(q);
              basis.evaluate(cell, xi, half_width, s);
              auto &list = pattern_nodes[s.pattern];
              if (!(known_patterns & (1u << s.pattern)))
                {
                  basis.node_pattern(cell, s, list, index_of);
                  known_patterns |= 1u << s.pattern;
                }
              s.nodes = list.data();
              kernel(p, q, s);
            }
        }
    }

  private:
    /// Half-width of a point's domain in cells, per direction (GIMP).
    Tensor<1, dim>
    domain_half_width(const double *q) const
    {
      const FieldLayout &l  = points.layout();
      const double       l0 = initial_half_width_of_body[q[l.body]];
      Tensor<1, dim>     half_width;
      if (basis_type == BasisType::cpgimp)
        {
          // The axis-aligned box around the deformed domain F [-l0, l0]^dim:
          // exact for stretches along the axes, and never degenerate under
          // rotation (the diagonal of F alone would vanish at 90 degrees).
          // It is capped at half a cell, where the GIMP stencil ends.
          const Tensor<1, dim> &h = grid.cell_size();
          const double         *F = q + l.deformation_gradient;
          for (unsigned int d = 0; d < dim; ++d)
            {
              double extent = 0;
              for (unsigned int e = 0; e < dim; ++e)
                extent += std::abs(F[d * dim + e]) * h[e];
              half_width[d] = std::clamp(l0 * extent / h[d], 1e-6, 0.5);
            }
        }
      else
        for (unsigned int d = 0; d < dim; ++d)
          half_width[d] = l0;
      return half_width;
    }

    const BackgroundGrid<dim> &grid;
    MaterialPoints<dim>       &points;
    const BasisType            basis_type;
    /// uGIMP/cpGIMP: initial domain half-width of each body's points, in
    /// cells: half of 1 / (points per cell).
    std::vector<double> initial_half_width_of_body;
  };
} // namespace mpm

#endif
