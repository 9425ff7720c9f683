#ifndef mpm_time_integrator_templates_h
#define mpm_time_integrator_templates_h

// The particle loops of the step and the helpers their kernels call,
// shared by the translation units of the integrator's stages: templates on
// the basis, instantiated where they are used, so the loops have no
// virtual calls and every kernel is inlined into its loop.
#include <mpm/parameters.h>
#include <mpm/time_integrator.h>
#include <mpm/transfer/transfers.h>

#include <algorithm>
#include <sstream>

namespace mpm
{
  /// The length of the local array of a nodal vector: owned and ghost
  /// entries (loops that clear or copy all of them).
  inline unsigned int
  n_local_entries(const LinearAlgebra::distributed::Vector<double> &v)
  {
    return v.locally_owned_size() + v.get_partitioner()->n_ghost_indices();
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
  template <int dim>
  template <typename Basis, typename Kernel>
  inline void
  TimeIntegrator<dim>::for_each_point(const Basis &basis, const Kernel &kernel)
  {
    typename Basis::Stencil s;
    Tensor<1, dim>          half_width;
    // The node lists of the patterns seen so far in the current cell: the
    // lookup of nodal-vector indices is done once per cell and pattern
    // (the points of a cell are mostly stored together).
    std::array<std::array<unsigned int, Basis::n_nodes>, Basis::n_patterns>
                                                  pattern_nodes;
    Particles::ParticleHandler<dim>              &particles = points.handler();
    typename BackgroundGrid<dim>::CellCoordinates cell, last_cell, first;
    // The stencil's nodes are looked up in the tile's node block (the
    // tile's nodes and one layer around them): one load per node.
    const unsigned int *block = nullptr;
    const auto index_of       = [&](const std::array<unsigned int, dim> &node) {
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


  template <int dim>
  inline Tensor<1, dim>
  TimeIntegrator<dim>::domain_half_width(const double *q) const
  {
    const FieldLayout &l  = points.layout();
    const double       l0 = initial_half_width_of_body[q[l.body]];
    Tensor<1, dim>     half_width;
    if (prm.basis == BasisType::cpgimp)
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



  template <int dim>
  template <typename Stencil>
  inline Tensor<2, dim>
  TimeIntegrator<dim>::velocity_gradient(const Stencil     &s,
                                         const double      *u,
                                         const unsigned int stride,
                                         const unsigned int slot,
                                         const double       light_mass) const
  {
    Tensor<1, dim> v_point;
    for (unsigned int v = 0; v < s.weights.size(); ++v)
      v_point +=
        s.weights[v] * Fields::vector<dim>(u + stride * s.nodes[v] + slot);
    // Sum of (v_I - v_point) grad phi_I: equal to sum v_I grad phi_I, since
    // the gradients sum to zero, but light nodes can now be left out. With
    // USL and the linear basis they must be: a node that only the edge of
    // a point's support reaches has a tiny mass phi m_p but a full force
    // V sigma grad phi, so its force-updated velocity grows as 1 / phi; in
    // the point's velocity it counts with phi, here with grad phi. The
    // internal force then leaves them out too (light_node_gradients).
    // Massless nodes (light_mass 0) have no velocity at all; they lie in
    // a stencil only where a point lies on a cell face, weight 0.
    Tensor<2, dim> L;
    for (unsigned int v = 0; v < s.weights.size(); ++v)
      {
        const double *node = u + stride * s.nodes[v];
        if (node[node_mass] > light_mass)
          L += outer_product(Fields::vector<dim>(node + slot) - v_point,
                             s.gradients[v]);
      }
    return L;
  }


  template <int dim>
  template <typename F>
  inline void
  TimeIntegrator<dim>::with_scene_basis(const F &f) const
  {
    with_basis<dim>(prm.basis, [&](auto *tag) {
      using Basis = std::remove_pointer_t<decltype(tag)>;
      f(Basis(grid.parameters().n_cells, grid.cell_size()));
    });
  }


} // namespace mpm

#endif
