// The transfer to the grid (P2G): each point's mass, momentum (APIC: its
// affine velocity field sampled at the node) and force (its stress, body
// force and point loads) scattered to the nodes of its stencil, with the
// small-mass guard's forces; the virtual fluid's forces on the wetted
// surface; and the check that the forces are the strain rate's adjoint.
#include <mpm/transfer/particle_to_grid.h>
#include <mpm/transfer/transfers.h>

#include <cmath>
#include <type_traits>

namespace mpm
{
  namespace
  {
    /**
     * The strain rate with the guard, L(w) = sum_{I heavy} (w_I - w_p) (x)
     * grad phi_I with w_p = sum_J phi_J w_J over all nodes, is linear in
     * the nodal velocities w. Its adjoint, the force whose work
     * sum_J f_J . w_J is -V sigma : L(w) for every w, gives node J the
     * stress term V sigma with the gradient
     *   grad phi_J [J heavy] + phi_J G,   G = sum_{K light} grad phi_K:
     * the light nodes' gradients spread over the stencil by the weights.
     * These still sum to zero (the gradients of all nodes do, and the
     * weights sum to one), so momentum is kept; and a light node's force
     * now scales with phi_J, as its mass does, so its force-updated
     * velocity stays bounded. The basis' gradients with the guard on the
     * strain rate's side only gave parting bodies energy: two disks +5 %
     * (MUSL) and +9 % (USF), before the guard was kept to USL.
     */
    template <int dim, typename Stencil, std::size_t n_nodes>
    inline bool
    light_node_gradients(const Stencil                       &s,
                         const double                        *u,
                         const unsigned int                   stride,
                         const double                         light_mass,
                         std::array<Tensor<1, dim>, n_nodes> &spread)
    {
      std::array<bool, n_nodes> light;
      Tensor<1, dim>            light_gradients;
      bool                      any_light = false;
      for (unsigned int v = 0; v < n_nodes; ++v)
        {
          light[v] =
            u[stride * s.nodes[v] + NodalLayout<dim>::node_mass] <= light_mass;
          if (light[v])
            {
              light_gradients += s.gradients[v];
              any_light = true;
            }
        }
      if (!any_light)
        return false;
      for (unsigned int v = 0; v < n_nodes; ++v)
        spread[v] = s.weights[v] * light_gradients +
                    (light[v] ? Tensor<1, dim>() : s.gradients[v]);
      return true;
    }
  } // namespace


  template <int dim>
  ParticleToGrid<dim>::ParticleToGrid(const StepParts<dim> &parts,
                                      ExternalLoads<dim>   &loads)
    : prm(parts.parameters)
    , grid(parts.grid)
    , points(parts.points)
    , loop(parts.loop)
    , nodes(parts.nodes)
    , loads(loads)
    , contact(parts.contact)
    , virtual_fluid(parts.virtual_fluid)
    , context(parts.context)
    , density_of_body(deformable_densities(points.bodies()))
    , cell_averages(grid, points)
  {
  }


  template <int dim>
  void
  ParticleToGrid<dim>::reinit()
  {
    if (virtual_fluid)
      {
        fluid_volume.reinit(grid.make_partitioner(1));
        support_volume.reinit(grid.make_partitioner(1));
        for (unsigned int i = 0; i < grid.n_locally_owned_nodes(); ++i)
          support_volume.local_element(i) = grid.node_support_volume(i);
        support_volume.update_ghost_values();
      }
  }


  template <int dim>
  template <typename Basis>
  void
  ParticleToGrid<dim>::scatter(const Basis &basis,
                               const bool   mass_and_momentum,
                               const bool   forces,
                               const double light_mass)
  {
    TimerOutput::Scope scope(context.timer, "P2G");
    double            *g         = nodes.sums.get_values();
    const unsigned int n_entries = n_local_entries(nodes.sums);
    for (unsigned int i = 0; i < n_entries; i += Layout::n_sums)
      {
        if (mass_and_momentum)
          for (unsigned int c = Layout::mass; c < Layout::force; ++c)
            g[i + c] = 0;
        if (forces)
          for (unsigned int c = Layout::force; c < Layout::n_sums; ++c)
            g[i + c] = 0;
      }
    const bool with_gradients = contact && mass_and_momentum;
    if (with_gradients)
      nodes.contact_data = 0.;
    // Empty without contact; read once, as the nodal sums are.
    double *contact_data = nodes.contact_data.begin();

    const FieldLayout   &l       = points.layout();
    const Tensor<1, dim> gravity = prm.gravity;
    // Local copies: the compiler cannot tell that the members do not change
    // while the loop writes the nodal sums through a double *.
    const bool with_body_forces   = loads.has_body_forces();
    double     power              = 0; // of the body forces
    const bool with_point_loads   = l.point_load != FieldLayout::absent;
    const bool with_surface_loads = l.load_moment != FieldLayout::absent;
    const bool with_f_bar = l.mean_stress_correction != FieldLayout::absent;
    if (forces && with_f_bar)
      cell_averages.average_mean_stress();
    const unsigned int  fields_per_node = nodes.n_fields;
    const unsigned int *fields_of_body  = nodes.field_of_body.data();
    // The nodal masses of the guard (light_mass > 0), ghosted.
    const double *velocities = nodes.velocities.get_values();
    loads.set_body_force_time(context.t);
    // Compiled once for one field and once for several, so that a scene
    // without contact carries nothing of it.
    // The guard's gradients (light_node_gradients), filled only where a
    // stencil has a light node: scratch kept out of the point loop, which
    // would otherwise zero it for every point.
    std::array<Tensor<1, dim>, Basis::n_nodes> spread;
    auto scatter = [&](auto transfer, auto several_fields) {
      using Transfer             = decltype(transfer);
      constexpr bool multi_field = decltype(several_fields)::value;
      loop.for_each_point(basis, [&](auto &p, const double *q, const auto &s) {
        const double m     = q[l.mass];
        unsigned int field = 0;
        if constexpr (multi_field)
          field = fields_of_body[static_cast<unsigned int>(q[l.body])];
        // The nodal sums of stencil node v, in this point's field.
        auto sums_of = [&](const unsigned int v) {
          if constexpr (multi_field)
            return g + Layout::n_sums * (fields_per_node * s.nodes[v] + field);
          else
            return g + Layout::n_sums * s.nodes[v];
        };
        if (mass_and_momentum)
          {
            const Tensor<1, dim> mv = m * Fields::vector<dim>(q + l.velocity);
            const Tensor<2, dim> mC =
              Transfer::template affine_momentum<dim>(m, q, l);
            for (unsigned int v = 0; v < Basis::n_nodes; ++v)
              {
                double              *node = sums_of(v);
                const Tensor<1, dim> p =
                  Transfer::momentum_at_node(mv, mC, s, v);
                node[Layout::mass] += s.weights[v] * m;
                for (unsigned int d = 0; d < dim; ++d)
                  node[Layout::momentum + d] += s.weights[v] * p[d];
              }
            // Contact normals of each field, and how many of its points'
            // domains (a box of side V^(1/dim) around each) hold the node:
            // where a body's surface lies on the grid.
            if constexpr (multi_field)
              if (with_gradients)
                {
                  const double half_side =
                    0.5 * (1 + 1e-9) * std::pow(q[l.volume], 1. / dim);
                  // A rigid body's normal is the gradient of its volume,
                  // not of its mass: its density must not change how it
                  // acts (with 1e-300 the products underflowed and the
                  // floor stopped acting).
                  const double weight =
                    density_of_body[static_cast<unsigned int>(q[l.body])] > 0
                      ? m
                      : q[l.volume];
                  for (unsigned int v = 0; v < Basis::n_nodes; ++v)
                    {
                      double *data =
                        contact_data + MultiFieldContact<dim>::data_per_field *
                                         nodes.slot_of(s.nodes[v], field);
                      for (unsigned int d = 0; d < dim; ++d)
                        data[d] += weight * s.gradients[v][d];
                      const Tensor<1, dim> r      = s.node_offset(v);
                      bool                 inside = true;
                      for (unsigned int d = 0; d < dim; ++d)
                        inside = inside && std::abs(r[d]) <= half_side;
                      data[dim] += inside;
                    }
                }
          }
        if (forces)
          {
            // Internal force with the current volume and Cauchy stress
            // (with F-bar, its cell's mean stress: FBar).
            SymmetricTensor<2, dim> sigma =
              Fields::symmetric<dim>(q + l.stress);
            if (with_f_bar)
              for (unsigned int d = 0; d < dim; ++d)
                sigma[d][d] += q[l.mean_stress_correction];
            const SymmetricTensor<2, dim> Vsigma = q[l.volume] * sigma;
            const bool                    guarded =
              light_mass > 0 &&
              light_node_gradients<dim>(
                s,
                velocities + (multi_field ? Layout::n_velocities * field : 0),
                multi_field ? fields_per_node * Layout::n_velocities
                            : Layout::n_velocities,
                light_mass,
                spread);
            const auto    &gradients = guarded ? spread : s.gradients;
            Tensor<1, dim> mg        = m * gravity;
            if (with_body_forces)
              {
                const Tensor<1, dim> b = loads.body_force(q);
                loads.check_load(b.norm(),
                                 q[l.body],
                                 "body force",
                                 p->get_location());
                const Tensor<1, dim> mb = m * b;
                mg += mb;
                power += mb * Fields::vector<dim>(q + l.velocity);
              }
            if (with_point_loads)
              mg += Fields::vector<dim>(q + l.point_load);
            auto add_forces = [&](const auto &stress_term) {
              for (unsigned int v = 0; v < Basis::n_nodes; ++v)
                {
                  const Tensor<1, dim> f =
                    s.weights[v] * mg - stress_term * gradients[v];
                  double *node = sums_of(v) + Layout::force;
                  for (unsigned int d = 0; d < dim; ++d)
                    node[d] += f[d];
                }
            };
            // A surface load F acts at the surface, d from the point:
            // F phi(x + d) = F phi(x) + (F (x) d) grad phi(x) to first
            // order (exact within a cell for the linear basis), so the
            // moment F (x) d joins the stress term; the point load holds
            // F phi(x). The quadratic B-spline takes phi(x + d) itself
            // where its functions reach x + d as one piece each
            // (Basis::weights_at): to first order its node beyond the
            // surface, which holds 1/16 of a point's mass, is 1/32 F out of
            // balance with the top points' stress, and pure FLIP let that
            // grow until the energy guard stopped the loaded column; exact,
            // it balances (0.028-0.064 over the schemes and transfers).
            // The other bases measure better to first order (cubic
            // B-spline 0.040-0.047 against 0.046-0.126; uGIMP 0.020 against
            // 0.034, whose weight averages over the point's domain).
            if (with_surface_loads)
              {
                const Tensor<2, dim> moment =
                  Fields::tensor<dim>(q + l.load_moment);
                const Tensor<1, dim> d =
                  Fields::vector<dim>(q + l.surface_offset);
                std::array<double, Basis::n_nodes> at_surface;
                if (moment.norm_square() > 0 &&
                    basis.weights_at(s, d, at_surface))
                  {
                    // moment = F (x) d
                    const Tensor<1, dim> F = moment * d / (d * d);
                    for (unsigned int v = 0; v < Basis::n_nodes; ++v)
                      {
                        double *node = sums_of(v) + Layout::force;
                        for (unsigned int c = 0; c < dim; ++c)
                          node[c] += (at_surface[v] - s.weights[v]) * F[c];
                      }
                    add_forces(Vsigma);
                  }
                else if (!guarded)
                  add_forces(Tensor<2, dim>(Vsigma) - moment);
                else
                  {
                    // The load's moment is no stress: the basis' gradients.
                    add_forces(Vsigma);
                    for (unsigned int v = 0; v < Basis::n_nodes; ++v)
                      {
                        const Tensor<1, dim> f    = moment * s.gradients[v];
                        double              *node = sums_of(v) + Layout::force;
                        for (unsigned int d = 0; d < dim; ++d)
                          node[d] += f[d];
                      }
                  }
              }
            else
              add_forces(Vsigma);
          }
      });
    };
    // Compiled for each transfer as well: the PIC/FLIP loop carries nothing
    // of APIC's.
    with_transfer(prm.transfer, [&](auto transfer) {
      if (nodes.n_fields > 1)
        scatter(transfer, std::true_type());
      else
        scatter(transfer, std::false_type());
    });
    if (forces)
      loads.set_body_force_power(power);
    nodes.sums.compress(VectorOperation::add);
    if (with_gradients)
      nodes.contact_data.compress(VectorOperation::add);
    if (forces && virtual_fluid)
      add_fluid_forces(basis);
  }


  /**
   * The virtual stress method (cl-mpm): the force of a pressure p on the
   * surface of a body, f_I = -int_dOmega p n phi_I dA, is by the divergence
   * theorem -int_Omega (p grad phi_I + phi_I grad p) dV, an integral over
   * the body that the points evaluate like the internal force, with the
   * "virtual stress" -p I. It needs no surface: the surface is wherever
   * the points end. For a node whose support lies inside the body the exact
   * integral vanishes, so only nodes whose support the wetted bodies do
   * not fill (to 0.1 %) get it; inside, the point quadrature would only
   * add its error, which the pressure's kink at the fluid's level makes
   * large. The threshold must be tight: a node just inside the surface
   * has its support's edge outside, a sliver of little volume but a
   * share of the surface force that is not small, most of all with the
   * quadratic B-spline (uncovered volume ~ d^3 / 6, weight on the surface
   * ~ d^2 / 2, d the sliver's width in cells). A point lattice that is
   * undisturbed covers an inner node's support exactly (the midpoint rule
   * integrates each piece of the basis, the errors cancel), so 0.1 %
   * leaves only distortion to tell apart. Floating block, draft error at
   * 16 / 32 cells: quadratic B-spline 0.50 % / 0.11 % with this mask
   * (7.3 % / 4.4 % with 1 %, 8.4 % / 0.74 % with every node); linear
   * 0.05 %, uGIMP (32) 0.08 %, as with 1 %; 19 % with a 10 % threshold.
   */
  template <int dim>
  template <typename Basis>
  void
  ParticleToGrid<dim>::add_fluid_forces(const Basis &basis)
  {
    TimerOutput::Scope scope(context.timer, "virtual fluid");
    const FieldLayout &l = points.layout();
    fluid_volume         = 0.;
    loop.for_each_point(basis, [&](auto &, const double *q, const auto &s) {
      if (virtual_fluid->wets(q[l.body]))
        for (unsigned int v = 0; v < Basis::n_nodes; ++v)
          fluid_volume.local_element(s.nodes[v]) += s.weights[v] * q[l.volume];
    });
    fluid_volume.compress(VectorOperation::add);
    fluid_volume.update_ghost_values();

    auto on_surface = [&](const unsigned int node) {
      return fluid_volume.local_element(node) <
             (1. - 1e-3) * support_volume.local_element(node);
    };
    nodes.fluid_force = 0.;
    virtual_fluid->set_time(context.t);
    loop.for_each_point(basis, [&](auto &p, const double *q, const auto &s) {
      if (!virtual_fluid->wets(q[l.body]))
        return;
      bool near_surface = false;
      for (unsigned int v = 0; v < Basis::n_nodes; ++v)
        near_surface = near_surface || on_surface(s.nodes[v]);
      if (!near_surface)
        return;
      Tensor<1, dim> grad_p;
      const double   pressure =
        virtual_fluid->pressure(p->get_location(), grad_p);
      if (pressure == 0 && grad_p.norm_square() == 0)
        return;
      const double V = q[l.volume];
      for (unsigned int v = 0; v < Basis::n_nodes; ++v)
        if (on_surface(s.nodes[v]))
          {
            const Tensor<1, dim> f =
              -V * (pressure * s.gradients[v] + s.weights[v] * grad_p);
            for (unsigned int d = 0; d < dim; ++d)
              nodes.fluid_force.local_element(
                dim * nodes.slot_of(s.nodes[v], nodes.field_of(q)) + d) += f[d];
          }
    });
    nodes.fluid_force.compress(VectorOperation::add);

    double *g               = nodes.sums.get_values();
    nodes.fluid_force_total = Tensor<1, dim>();
    for (unsigned int i = 0; i < nodes.n_owned_slots(); ++i)
      for (unsigned int d = 0; d < dim; ++d)
        {
          const double f = nodes.fluid_force.local_element(dim * i + d);
          g[Layout::n_sums * i + Layout::force + d] += f;
          nodes.fluid_force_total[d] += f;
        }
  }


  // Instantiated for each dimension and basis.
#define MPM_INSTANTIATE_BASIS(dim, Basis)                   \
  template void ParticleToGrid<dim>::scatter(const Basis &, \
                                             const bool,    \
                                             const bool,    \
                                             const double);
  MPM_INSTANTIATE_WITH_EACH_BASIS(ParticleToGrid, MPM_INSTANTIATE_BASIS)
#undef MPM_INSTANTIATE_BASIS
} // namespace mpm
