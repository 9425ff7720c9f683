#ifndef mpm_transfer_strain_rate_h
#define mpm_transfer_strain_rate_h

// The strain rate L at a point from nodal velocities, with the small-mass
// guard: inline, for the loops of G2P and of the adjoint check.
#include <deal.II/base/tensor.h>

#include <mpm/field_layout.h>
#include <mpm/grid/nodal_layout.h>
#include <mpm/integrator_parameters.h>

namespace mpm
{
  using namespace dealii;

  /**
   * The mass at or below which a node is left out of the strain rate:
   * @p guard_mass (the small-mass guard) where the strain rate reads
   * force-updated velocities (USL, @p scheme) through gradients that do
   * not vanish with the weights (the linear basis), else none. The
   * transferred velocities of MUSL and USF are mass-weighted means of the
   * points' velocities, and with a smooth basis a light node's velocity,
   * growing as 1 / phi, enters the strain rate with grad phi, which
   * vanishes as phi^(1/2) or faster.
   */
  template <typename Basis>
  inline double
  strain_rate_light_mass(const UpdateScheme scheme, const double guard_mass)
  {
    return scheme == UpdateScheme::USL && !Basis::gradient_vanishes_with_weight
             ? guard_mass
             : 0.;
  }


  /**
   * L at a point (stencil @p s) from the nodal velocities in @p slot of
   * the nodal array @p u (the point's field, node stride @p stride). Nodes
   * of mass <= @p light_mass are left out (strain_rate_light_mass).
   *
   * Always inlined: left to the compiler, the loops call one out-of-line
   * copy, the one the linker keeps from whichever unit it meets first, and
   * the QBS/APIC gather ran 5-7 % slower with it (issue 31, measured).
   */
  template <int dim, typename Stencil>
  DEAL_II_ALWAYS_INLINE inline Tensor<2, dim>
  velocity_gradient(const Stencil     &s,
                    const double      *u,
                    const unsigned int stride,
                    const unsigned int slot,
                    const double       light_mass)
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
        if (node[NodalLayout<dim>::node_mass] > light_mass)
          L += outer_product(Fields::vector<dim>(node + slot) - v_point,
                             s.gradients[v]);
      }
    return L;
  }
} // namespace mpm

#endif
