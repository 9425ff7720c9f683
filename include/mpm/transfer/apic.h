#ifndef mpm_transfer_apic_h
#define mpm_transfer_apic_h

#include <deal.II/base/tensor.h>

#include <mpm/field_layout.h>
#include <mpm/grid/nodal_layout.h>
#include <mpm/transfer/deformation_increment.h>
#include <mpm/transfer/gather_state.h>

#include <array>

namespace mpm
{
  using namespace dealii;

  /**
   * APIC's C_p = sum_I v_I (x) a_I (Jiang et al. 2015) from the nodal
   * velocities at @p slot of the interleaved array @p u (node stride
   * @p stride); @p affine is scratch for the basis' affine weights a_I.
   * Every node counts, light ones too: only then does the transfer keep
   * angular momentum exactly (tests/rigid_rotation.cc). The gather and the
   * macro step's reset form C_p here.
   */
  template <int dim, typename Basis>
  inline DEAL_II_ALWAYS_INLINE Tensor<2, dim>
                               apic_velocity_gradient(const Basis                                &basis,
                                                      const typename Basis::Stencil              &s,
                                                      const double                               *u,
                                                      const unsigned int                          stride,
                                                      const unsigned int                          slot,
                                                      std::array<Tensor<1, dim>, Basis::n_nodes> &affine)
  {
    basis.affine_weights(s, affine);
    Tensor<2, dim> C;
    for (unsigned int v = 0; v < Basis::n_nodes; ++v)
      C += outer_product(Fields::vector<dim>(u + stride * s.nodes[v] + slot),
                         affine[v]);
    return C;
  }


  /**
   * The gradient of an affine velocity field v_p + C (x - x_p) once the
   * material it describes has moved with it for @p dt: the velocities stay
   * with the material while the separations between its points grow by
   * I + dt C, so in the positions reached the gradient is
   * C (I + dt C)^{-1} (in 1D C / (1 + dt C): a free cloud spreads as
   * 1 / t). The transfers themselves would keep C as it is, which is only
   * right where forces hold it there; where none act (a point whose
   * stress is zero, e.g. cohesionless and separated) the field would
   * stretch the point at a constant rate, its J growing exponentially
   * instead of linearly: a single point sliding on a friction face was torn
   * apart (J > 1000 within 0.2 s) instead of stopping after
   * v^2 / (2 mu g). The gather stores this, with the step's dt, as the C_p
   * the next transfer to the grid uses. If I + dt C is singular the step
   * is unstable and its strain rate stops the run; C is then kept.
   */
  template <int dim>
  inline Tensor<2, dim>
  advected_affine_velocity(const Tensor<2, dim> &C, const double dt)
  {
    const Tensor<2, dim> stretch = deformation_increment(C, dt);
    const double         det     = determinant(stretch);
    return det > 0 ? Tensor<2, dim>(C * invert(stretch)) : C;
  }


  /**
   * A node that only the edge of a point's support reaches has a tiny
   * mass phi m_p but the full force V sigma grad phi, so the force update
   * gives it an increment dt f / m that grows as 1 / phi. In v_p it counts
   * with phi (a bounded share: momentum), but in APIC's C_p with the
   * affine weight a_I, which for the linear basis is grad phi and does not
   * vanish with phi. The next transfer then spreads m_p C_p (x_I - x_p)
   * from wherever the point has moved: the linear basis with APIC gained
   * energy until the energy guard stopped it, or not, depending on where
   * the output times cut the steps (two disks; benchmarks/contact).
   * At a node lighter than the small-mass threshold @p light_mass the
   * point's own
   * increment @p dv_point = sum_I phi_I dv_I (the gather's FLIP
   * increment) stands in for the node's: C_p still
   * reproduces any affine transferred field and any uniform acceleration,
   * and v_p is unchanged, so momentum is too. A node without mass has no
   * velocity at all, yet it is in the stencil of a point that lies on its
   * cell's face (weight 0, gradient full): there the point's own velocity
   * @p v_point stands in (without this, the points on a translating disk's
   * edge got |C_p| = 2 |v| / h whenever a step ended with them on a node
   * line). Smooth bases do not need it (a_I vanishes with phi there;
   * measured: the rule would only take 0.4-1.3 % of the two disks'
   * energy).
   */
  template <int dim, typename Stencil, std::size_t n_nodes>
  inline void
  discount_light_node_increments(
    const Stencil                             &s,
    const double                              *u,
    const unsigned int                         stride,
    const std::array<Tensor<1, dim>, n_nodes> &affine,
    const Tensor<1, dim>                      &v_point,
    const Tensor<1, dim>                      &dv_point,
    const double                               light_mass,
    Tensor<2, dim>                            &C)
  {
    constexpr unsigned int node_mass = NodalLayout<dim>::node_mass;
    constexpr unsigned int v_old     = NodalLayout<dim>::v_old;
    constexpr unsigned int v_new     = NodalLayout<dim>::v_new;
    for (unsigned int v = 0; v < n_nodes; ++v)
      {
        const double *node = u + stride * s.nodes[v];
        if (node[node_mass] > light_mass)
          continue;
        const Tensor<1, dim> v_I = Fields::vector<dim>(node + v_new);
        C -=
          outer_product(node[node_mass] == 0
                          ? v_I - v_point
                          : v_I - Fields::vector<dim>(node + v_old) - dv_point,
                        affine[v]);
      }
  }


  /**
   * The affine particle-in-cell transfer ('Simulation/transfer = APIC',
   * Jiang et al. 2015): each point keeps the affine velocity field
   * v_p + C_p (x - x_p) and gives each node its value there; it takes back
   * the grid velocity at the point and C_p = sum_I v_I (x) a_I. It keeps
   * angular momentum exactly and dissipates far less than PIC. See
   * FlipPicBlend for what the members are.
   */
  struct AffineParticleInCell
  {
    static constexpr const char *name                   = "APIC";
    static constexpr bool        blends_pic             = false;
    static constexpr bool        stores_affine_velocity = true;

    /// The increment only stands in at the light nodes of a basis whose
    /// affine weights do not vanish with the weights (the linear one).
    template <typename Basis>
    static constexpr bool
    needs_increment()
    {
      return !Basis::gradient_vanishes_with_weight;
    }

    template <int dim>
    static Tensor<2, dim>
    affine_momentum(const double m, const double *q, const FieldLayout &l)
    {
      return m * Fields::tensor<dim>(q + l.affine_velocity);
    }

    /// The point's velocity field v_p + C_p (x - x_p), sampled at the
    /// node (times m_p).
    template <int dim, typename Stencil>
    static Tensor<1, dim>
    momentum_at_node(const Tensor<1, dim> &mv,
                     const Tensor<2, dim> &mC,
                     const Stencil        &s,
                     const unsigned int    v)
    {
      return mv + mC * s.node_offset(v);
    }

    /// v_p is the grid velocity at the point; C_p = B_p D_p^{-1}.
    template <int dim, typename Basis>
    static void
    update_point(const Basis                                &basis,
                 const typename Basis::Stencil              &s,
                 const double                               *u,
                 const unsigned int                          stride,
                 double                                     *q,
                 const FieldLayout                          &l,
                 const Tensor<1, dim>                       &v_grid,
                 const Tensor<1, dim>                       &dv_grid,
                 const GatherState                          &c,
                 std::array<Tensor<1, dim>, Basis::n_nodes> &affine)
    {
      Fields::store(v_grid, q + l.velocity);
      Tensor<2, dim> C = apic_velocity_gradient<dim>(
        basis, s, u, stride, NodalLayout<dim>::v_new, affine);
      if constexpr (!Basis::gradient_vanishes_with_weight)
        discount_light_node_increments(
          s, u, stride, affine, v_grid, dv_grid, c.light_mass, C);
      Fields::store(advected_affine_velocity(C, c.dt), q + l.affine_velocity);
    }
  };
} // namespace mpm

#endif
