// The transfer back to the points (G2P): their velocities by the scene's
// transfer (transfer/flip_pic.h, transfer/apic.h), positions, and
// kinematics (the strain rate L, the volume and F from I + dt L).
#include <mpm/transfer/deformation_increment.h>
#include <mpm/transfer/grid_to_particle.h>
#include <mpm/transfer/strain_rate.h>
#include <mpm/transfer/transfers.h>

#include <sstream>
#include <type_traits>

namespace mpm
{
  template <int dim>
  GridToParticle<dim>::GridToParticle(const StepParts<dim> &parts,
                                      const double          guard_mass)
    : prm(parts.parameters)
    , points(parts.points)
    , loop(parts.loop)
    , nodes(parts.nodes)
    , guard_mass(guard_mass)
    , context(parts.context)
  {
    const auto &g = parts.grid.parameters();
    for (unsigned int f = 0; f < 2 * dim; ++f)
      if (is_rough(g.boundary[f]))
        {
          const unsigned int axis = f / 2;
          // The widest reach of the scene's basis (GIMP with one point per
          // cell): a point further away touches none of the face's nodes.
          rough_faces.push_back(
            {axis,
             f % 2 == 0 ? g.lower_corner[axis] : g.upper_corner[axis],
             support_reach(prm.basis, 0.5) * parts.grid.cell_size()[axis]});
        }
  }


  /**
   * APIC's v_p is the grid's velocity at the point; what a point remembers
   * of its own motion is its affine field C_p. A cohesionless point that
   * has parted (opening > 0) has no stress, and alone near a fixed or
   * friction face its field holds momentum the face never sees: within
   * h/2 of the face the basis is linear (weights 1 - xi, xi), the field
   * vanishes at the face's nodes (C_yy = v_py / y_p) and puts all of the
   * point's momentum into the face, and of its slide along it, on the light
   * node row above, which gravity then speeds up step after step. The
   * face's nodes see neither, so a point on a face inclined below its
   * friction angle slid on and was torn apart (J > 1000; session 27's
   * trace, benchmarks/granular/README.md). Without the part of C_p along
   * the normal, the point gives the face nodes its own velocity, as FLIP
   * does, and the face holds it.
   *
   * Only a point alone: in the thin sheet at a collapse's front many
   * parted points flow along the floor, and their shear across it lives
   * in C_p alone; taking it from every parted point near the face damped
   * that sheet like PIC (the Bui toe fell from 0.460 to 0.335 m). A point
   * is alone where its own mass is most of what its nodes hold:
   * sum_I phi_I^2 m_p / m_I > 1/2 (1 for a point without neighbours; a
   * row of points along the floor is near 0.3).
   */
  template <int dim>
  template <typename Stencil>
  void
  GridToParticle<dim>::release_lone_point_at_rough_face(
    const Point<dim>  &x,
    const Stencil     &s,
    const double      *u,
    const unsigned int stride,
    double            *q) const
  {
    const FieldLayout &l = points.layout();
    for (const RoughFace &f : rough_faces)
      if (std::abs(x[f.axis] - f.coordinate) < f.reach)
        {
          double share = 0;
          for (unsigned int v = 0; v < s.weights.size(); ++v)
            {
              const double m_I = u[stride * s.nodes[v] + Layout::node_mass];
              if (m_I > 0)
                share += s.weights[v] * s.weights[v] * q[l.mass] / m_I;
            }
          if (share > 0.5)
            for (unsigned int i = 0; i < dim; ++i)
              q[l.affine_velocity + i * dim + f.axis] = 0;
        }
  }


  template <int dim>
  template <typename Basis>
  void
  GridToParticle<dim>::gather(const Basis &basis,
                              const double dt,
                              const bool   kinematics)
  {
    TimerOutput::Scope scope(context.timer, "G2P");
    const FieldLayout &l     = points.layout();
    const double      *u_all = nodes.velocities.get_values();
    // Newmark's gamma (USL, FLIP): see GridUpdate::velocities_after_forces.
    const GatherState state{dt,
                            prm.flip_fraction_of_step(dt),
                            kinematics && prm.newmark_gamma != 0.5,
                            1. / (prm.newmark_gamma + 0.5),
                            guard_mass};
    const double      light_mass =
      strain_rate_light_mass<Basis>(prm.scheme, guard_mass);
    std::array<Tensor<1, dim>, Basis::n_nodes> affine;
    const unsigned int                         fields_per_node = nodes.n_fields;
    const unsigned int *fields_of_body = nodes.field_of_body.data();
    // Only parted points alone near a rough face give up part of their
    // affine field (release_lone_point_at_rough_face): decided once here.
    const bool lone_point_rule =
      !rough_faces.empty() && l.opening != FieldLayout::absent;
    // Compiled once for each transfer and for one or several fields, so
    // that the PIC/FLIP loop carries nothing of APIC's, nor a scene
    // without contact anything of it.
    auto gather = [&](auto transfer, auto several_fields) {
      using Transfer                 = decltype(transfer);
      constexpr bool     multi_field = decltype(several_fields)::value;
      const unsigned int stride      = multi_field
                                         ? fields_per_node * Layout::n_velocities
                                         : Layout::n_velocities;
      loop.for_each_point(basis, [&](auto &p, double *q, const auto &s) {
        const double *u = u_all;
        if constexpr (multi_field)
          u += Layout::n_velocities *
               fields_of_body[static_cast<unsigned int>(q[l.body])];
        Tensor<1, dim> v_grid, dv_grid;
        for (unsigned int v = 0; v < Basis::n_nodes; ++v)
          {
            const double        *node = u + stride * s.nodes[v];
            const Tensor<1, dim> b = Fields::vector<dim>(node + Layout::v_new);
            v_grid += s.weights[v] * b;
            if constexpr (Transfer::template needs_increment<Basis>())
              dv_grid +=
                s.weights[v] * (b - Fields::vector<dim>(node + Layout::v_old));
          }
        Transfer::template update_point<dim, Basis>(
          basis, s, u, stride, q, l, v_grid, dv_grid, state, affine);
        if constexpr (Transfer::stores_affine_velocity)
          if (lone_point_rule && q[l.opening] > 0)
            release_lone_point_at_rough_face(
              p->get_location(), s, u, stride, q);
        p->set_location(p->get_location() + dt * v_grid);
        if (kinematics)
          apply_velocity_gradient(
            p,
            q,
            velocity_gradient<dim>(s, u, stride, Layout::v_new, light_mass),
            dt);
      });
    };
    with_transfer(prm.transfer, [&](auto transfer) {
      if (nodes.n_fields > 1)
        gather(transfer, std::true_type());
      else
        gather(transfer, std::false_type());
    });
  }


  template <int dim>
  template <typename Basis>
  void
  GridToParticle<dim>::update_kinematics(const Basis       &basis,
                                         const double       dt,
                                         const unsigned int slot)
  {
    TimerOutput::Scope scope(context.timer, "G2P");
    // Read once: the loop reaches the nodal state through a reference.
    const double      *u      = nodes.velocities.get_values();
    const unsigned int stride = nodes.n_fields * Layout::n_velocities;
    loop.for_each_point(basis, [&](auto &p, double *q, const auto &s) {
      apply_velocity_gradient(
        p,
        q,
        velocity_gradient<dim>(
          s, u + Layout::n_velocities * nodes.field_of(q), stride, slot, 0.),
        dt);
    });
  }


  template <int dim>
  template <typename Iterator>
  inline void
  GridToParticle<dim>::apply_velocity_gradient(const Iterator       &p,
                                               double               *q,
                                               const Tensor<2, dim> &L,
                                               const double          dt)
  {
    const FieldLayout &l = points.layout();
    Fields::store(L, q + l.velocity_gradient);
    const Tensor<2, dim> dF     = deformation_increment(L, dt);
    const double         det_dF = determinant(dF);
    if (!(det_dF > 0) && !context.failed())
      {
        std::ostringstream msg;
        msg << context.when() << ": material point " << p->get_id()
            << " of body " << q[l.body] << " at (" << p->get_location()
            << ") would invert: det(I + dt L) = " << det_dF
            << " <= 0 (J = det F would be "
            << (l.deformation_gradient != FieldLayout::absent
                  ? determinant(
                      Fields::tensor<dim>(q + l.deformation_gradient)) *
                      det_dF
                  : det_dF)
            << "); the run is unstable (try a smaller CFL number, MUSL, or "
               "damping)";
        context.fail(msg.str());
      }
    q[l.volume] *= det_dF;
    if (l.deformation_gradient != FieldLayout::absent)
      Fields::store(Tensor<2, dim>(
                      dF * Fields::tensor<dim>(q + l.deformation_gradient)),
                    q + l.deformation_gradient);
  }


  // Instantiated for each dimension and basis.
#define MPM_INSTANTIATE_BASIS(dim, Basis)                             \
  template void GridToParticle<dim>::gather(const Basis &,            \
                                            const double,             \
                                            const bool);              \
  template void GridToParticle<dim>::update_kinematics(const Basis &, \
                                                       const double,  \
                                                       const unsigned int);
  MPM_INSTANTIATE_WITH_EACH_BASIS(GridToParticle, MPM_INSTANTIATE_BASIS)
#undef MPM_INSTANTIATE_BASIS
} // namespace mpm
