// The transfer back to the points (G2P): their velocities (PIC/FLIP blend,
// Newmark's, or APIC's v_p and C_p), positions, and kinematics (the strain
// rate L, the volume and F from I + dt L), with the small-mass guard on
// APIC's C_p for the linear basis.
#include <mpm/time_integrator.h>
#include <mpm/time_integrator.templates.h>

#include <sstream>
#include <type_traits>

namespace mpm
{
  template <int dim>
  void
  TimeIntegrator<dim>::transfer_round_trip()
  {
    with_scene_basis([&](const auto &basis) {
      scatter_to_grid(basis, true, false);
      grid_velocities_from_momentum(v_old);
      // No force, no step: the new grid velocity is the old one.
      grid_velocities_from_momentum(v_new);
      gather_to_particles(basis, 0., false);
    });
    raise_if_any_failed(failure, comm);
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
   * At a node lighter than the small-mass threshold the point's own
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
  template <int dim>
  template <typename Stencil, std::size_t n_nodes>
  inline void
  TimeIntegrator<dim>::discount_light_node_increments(
    const Stencil                             &s,
    const double                              *u,
    const unsigned int                         stride,
    const std::array<Tensor<1, dim>, n_nodes> &affine,
    const Tensor<1, dim>                      &v_point,
    const Tensor<1, dim>                      &dv_point,
    Tensor<2, dim>                            &C) const
  {
    for (unsigned int v = 0; v < n_nodes; ++v)
      {
        const double *node = u + stride * s.nodes[v];
        if (!is_light(node))
          continue;
        const Tensor<1, dim> v_I = Fields::vector<dim>(node + v_new);
        C -=
          outer_product(node[node_mass] == 0
                          ? v_I - v_point
                          : v_I - Fields::vector<dim>(node + v_old) - dv_point,
                        affine[v]);
      }
  }


  template <int dim>
  template <typename Basis>
  void
  TimeIntegrator<dim>::gather_to_particles(const Basis &basis,
                                           const double dt,
                                           const bool   kinematics)
  {
    TimerOutput::Scope scope(timer, "G2P");
    const FieldLayout &l     = points.layout();
    const double      *u_all = grid_velocity.get_values();
    const double       alpha = prm.flip_fraction;
    // Newmark's gamma (USL, FLIP): see grid_velocities_after_forces.
    const bool   newmark          = kinematics && prm.newmark_gamma != 0.5;
    const double increment_factor = 1. / (prm.newmark_gamma + 0.5);
    std::array<Tensor<1, dim>, Basis::n_nodes> affine;
    const unsigned int                         fields_per_node = n_fields;
    const unsigned int *fields_of_body = field_of_body.data();
    // Compiled once for each transfer and for one or several fields, so
    // that the PIC/FLIP loop carries nothing of APIC's, nor a scene
    // without contact anything of it.
    auto gather = [&](auto apic, auto several_fields) {
      constexpr bool     multi_field = decltype(several_fields)::value;
      const unsigned int stride =
        multi_field ? fields_per_node * n_velocities : n_velocities;
      for_each_point(basis, [&](auto &p, double *q, const auto &s) {
        const double *u = u_all;
        if constexpr (multi_field)
          u +=
            n_velocities * fields_of_body[static_cast<unsigned int>(q[l.body])];
        Tensor<1, dim> v_grid, dv_grid;
        for (unsigned int v = 0; v < Basis::n_nodes; ++v)
          {
            const double        *node = u + stride * s.nodes[v];
            const Tensor<1, dim> b    = Fields::vector<dim>(node + v_new);
            v_grid += s.weights[v] * b;
            // FLIP's velocity increment; APIC uses it only for the light
            // nodes of the linear basis (discount_light_node_increments).
            if constexpr (!decltype(apic)::value ||
                          !Basis::gradient_vanishes_with_weight)
              dv_grid += s.weights[v] * (b - Fields::vector<dim>(node + v_old));
          }
        if constexpr (decltype(apic)::value)
          {
            // v_p is the grid velocity at the point; C_p = B_p D_p^{-1}.
            Fields::store(v_grid, q + l.velocity);
            Tensor<2, dim> C =
              apic_velocity_gradient<dim>(basis, s, u, stride, v_new, affine);
            if constexpr (!Basis::gradient_vanishes_with_weight)
              discount_light_node_increments(
                s, u, stride, affine, v_grid, dv_grid, C);
            Fields::store(advected_affine_velocity(C, dt),
                          q + l.affine_velocity);
          }
        else if (newmark)
          {
            // The nodes hold v_old + (gamma + 1/2) dt a: the velocity
            // update is dt a of it.
            const Tensor<1, dim> v_p = Fields::vector<dim>(q + l.velocity);
            const Tensor<1, dim> dv  = increment_factor * dv_grid;
            Fields::store(Tensor<1, dim>(alpha * (v_p + dv) +
                                         (1. - alpha) *
                                           (v_grid - dv_grid + dv)),
                          q + l.velocity);
          }
        else
          {
            const Tensor<1, dim> v_p = Fields::vector<dim>(q + l.velocity);
            Fields::store(Tensor<1, dim>(alpha * (v_p + dv_grid) +
                                         (1. - alpha) * v_grid),
                          q + l.velocity);
          }
        p->set_location(p->get_location() + dt * v_grid);
        if (kinematics)
          apply_velocity_gradient(
            p,
            q,
            velocity_gradient(
              s, u, stride, v_new, strain_rate_light_mass<Basis>()),
            dt);
      });
    };
    const bool apic = prm.transfer == Transfer::apic;
    if (n_fields > 1)
      {
        if (apic)
          gather(std::true_type(), std::true_type());
        else
          gather(std::false_type(), std::true_type());
      }
    else if (apic)
      gather(std::true_type(), std::false_type());
    else
      gather(std::false_type(), std::false_type());
  }


  template <int dim>
  template <typename Basis>
  void
  TimeIntegrator<dim>::update_kinematics(const Basis       &basis,
                                         const double       dt,
                                         const unsigned int slot)
  {
    TimerOutput::Scope scope(timer, "G2P");
    for_each_point(basis, [&](auto &p, double *q, const auto &s) {
      apply_velocity_gradient(p,
                              q,
                              velocity_gradient(s,
                                                grid_velocity.get_values() +
                                                  n_velocities * field_of(q),
                                                n_fields * n_velocities,
                                                slot,
                                                0.),
                              dt);
    });
  }


  template <int dim>
  template <typename Iterator>
  inline void
  TimeIntegrator<dim>::apply_velocity_gradient(const Iterator       &p,
                                               double               *q,
                                               const Tensor<2, dim> &L,
                                               const double          dt)
  {
    const FieldLayout &l = points.layout();
    Fields::store(L, q + l.velocity_gradient);
    Tensor<2, dim> dF = dt * L;
    for (unsigned int d = 0; d < dim; ++d)
      dF[d][d] += 1.;
    const double det_dF = determinant(dF);
    if (!(det_dF > 0) && failure.empty())
      {
        std::ostringstream msg;
        msg << "step " << n_steps << ", t = " << t << ": material point "
            << p->get_id() << " of body " << q[l.body] << " at ("
            << p->get_location() << ") would invert: det(I + dt L) = " << det_dF
            << " <= 0 (J = det F would be "
            << (l.deformation_gradient != FieldLayout::absent
                  ? determinant(
                      Fields::tensor<dim>(q + l.deformation_gradient)) *
                      det_dF
                  : det_dF)
            << "); the run is unstable (try a smaller CFL number, MUSL, or "
               "damping)";
        failure = msg.str();
      }
    q[l.volume] *= det_dF;
    if (l.deformation_gradient != FieldLayout::absent)
      Fields::store(Tensor<2, dim>(
                      dF * Fields::tensor<dim>(q + l.deformation_gradient)),
                    q + l.deformation_gradient);
  }


  // Members of TimeIntegrator defined here, instantiated for each dimension
  // and basis (the class itself is instantiated in time_integrator.cc).
#define MPM_INSTANTIATE_BASIS(dim, Basis)                               \
  template void TimeIntegrator<dim>::gather_to_particles(const Basis &, \
                                                         const double,  \
                                                         const bool);   \
  template void TimeIntegrator<dim>::update_kinematics(const Basis &,   \
                                                       const double,    \
                                                       const unsigned int);
#define MPM_INSTANTIATE(dim)                     \
  MPM_FOR_EACH_BASIS(MPM_INSTANTIATE_BASIS, dim) \
  template void TimeIntegrator<dim>::transfer_round_trip();
  MPM_INSTANTIATE(1)
  MPM_INSTANTIATE(2)
  MPM_INSTANTIATE(3)
#undef MPM_INSTANTIATE
#undef MPM_INSTANTIATE_BASIS
} // namespace mpm
