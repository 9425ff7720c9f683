#include <mpm/boundary_conditions/rigid_wall.h>
#include <mpm/parameters.h>

#include <cmath>

namespace mpm
{
  template <int dim>
  void
  RigidWallParameters<dim>::declare_parameters(ParameterHandler  &prm,
                                               const unsigned int index)
  {
    prm.enter_subsection("Boundary conditions");
    prm.enter_subsection("Rigid wall " + std::to_string(index));
    prm.declare_entry("point",
                      "0",
                      Patterns::Anything(),
                      "A point of the plane at t = 0, one value per "
                      "dimension.");
    prm.declare_entry("normal",
                      "0, 1, 0",
                      Patterns::Anything(),
                      "Normal of the plane, pointing to the side where the "
                      "material is; any non-zero length. 2D reads the first "
                      "two values.");
    prm.declare_entry("velocity",
                      "0",
                      Patterns::Anything(),
                      "Velocity of the plane in m/s (a moving wall).");
    prm.declare_entry("friction coefficient",
                      "0",
                      Patterns::Anything(),
                      "Coulomb coefficient mu >= 0 between wall and "
                      "material.");
    prm.declare_entry("penalty factor",
                      "1",
                      Patterns::Anything(),
                      "Contact stiffness kappa in (0, 4]: a point overlapping "
                      "the wall by delta is pushed back by kappa M "
                      "l^(dim-1) delta / h (M: p-wave modulus, l: point "
                      "size, h: cell size). Up to 4 keeps the contact "
                      "stable at the CFL step; larger is stiffer.");
    prm.declare_entry("damping ratio",
                      "0.5",
                      Patterns::Anything(),
                      "Normal damping of the contact as a fraction of "
                      "critical, in [0, 1]: 0 bounces, 1 absorbs.");
    prm.leave_subsection();
    prm.leave_subsection();
  }


  template <int dim>
  void
  RigidWallParameters<dim>::parse_parameters(ParameterHandler  &prm,
                                             const unsigned int index)
  {
    this->index            = index;
    const std::string name = "Rigid wall " + std::to_string(index);
    const std::string path = "Boundary conditions/" + name;
    prm.enter_subsection("Boundary conditions");
    prm.enter_subsection(name);
    {
      point = Parse::point<dim>(prm, path, "point");
      // The normal may be given with 3 components in any dimension.
      const auto values = Utilities::split_string_list(prm.get("normal"));
      if (values.size() != dim && values.size() != 3)
        throw InputError(path + "/normal",
                         prm.get("normal"),
                         "expects " + std::to_string(dim) +
                           (dim < 3 ? " (or 3)" : "") +
                           " comma-separated values");
      for (unsigned int d = 0; d < dim; ++d)
        try
          {
            normal[d] = Parse::number(values[d]);
          }
        catch (...)
          {
            throw InputError(path + "/normal",
                             prm.get("normal"),
                             "must be numbers");
          }
      // Only the direction counts: scaled by its largest component first,
      // a normal of tiny (or huge) components keeps it.
      double largest = 0;
      for (unsigned int d = 0; d < dim; ++d)
        largest = std::max(largest, std::abs(normal[d]));
      if (!(largest > 0) || !std::isfinite(largest))
        throw InputError(path + "/normal",
                         prm.get("normal"),
                         "must be a non-zero, finite vector");
      // (Component by component: Tensor's /= multiplies by 1 / largest,
      // which overflows for a subnormal largest.)
      for (unsigned int d = 0; d < dim; ++d)
        normal[d] = normal[d] / largest;
      normal /= normal.norm();
      velocity = Parse::vector<dim>(prm, path, "velocity");
      friction_coefficient =
        Parse::bounded_double(prm, path, "friction coefficient", 0, 1e300);
      penalty =
        Parse::bounded_double(prm, path, "penalty factor", 0, 4, true, false);
      damping_ratio = Parse::bounded_double(prm, path, "damping ratio", 0, 1);
    }
    prm.leave_subsection();
    prm.leave_subsection();
  }


  template <int dim>
  RigidWall<dim>::RigidWall(const RigidWallParameters<dim> &parameters,
                            const double                    cell_size,
                            const unsigned int              slip_slot)
    : MeteredReporter<dim>("wall" + std::to_string(parameters.index) + "_force")
    , prm(parameters)
    , h(cell_size)
    , slip_slot(slip_slot)
  {
  }


  template <int dim>
  void
  RigidWall<dim>::act_on_points(Particles::ParticleHandler<dim> &points,
                                const FieldLayout               &l,
                                const std::vector<double> &wave_modulus_of_body,
                                const double               t,
                                const double               dt)
  {
    const Tensor<1, dim> &n        = prm.normal;
    const Point<dim>      position = prm.point + t * prm.velocity;
    const double          mu       = prm.friction_coefficient;
    Tensor<1, dim>        reaction;
    const bool            friction = slip_slot != numbers::invalid_unsigned_int;
    const unsigned int    spring   = // this wall's stick spring in the point
      friction ? l.wall_slip + dim * slip_slot : 0;
    for (auto &p : points)
      {
        double      *q       = p.get_properties().data();
        double      *load    = q + l.point_load;
        const double overlap = -((p.get_location() - position) * n);
        if (!(overlap > 0))
          {
            if (friction)
              for (unsigned int d = 0; d < dim; ++d)
                q[spring + d] = 0;
            continue;
          }
        // Contact area l^(dim-1) of a point of size l = V^(1/dim).
        const double m = q[l.mass];
        const double k = prm.penalty * wave_modulus_of_body[q[l.body]] *
                         std::pow(q[l.volume], (dim - 1.) / dim) /
                         h; // N/m per point
        const Tensor<1, dim> relative =
          Fields::vector<dim>(q + l.velocity) - prm.velocity;
        const double approach = relative * n; // < 0: moving into it
        // A contact pushes, never pulls.
        const double damping = 2 * prm.damping_ratio * std::sqrt(k * m);
        const double normal_force =
          std::max(0., k * overlap - damping * approach);
        Tensor<1, dim> f = normal_force * n;

        if (friction)
          {
            // Stick spring on the tangential displacement, in the plane,
            // damped like the normal direction so that a stuck body does
            // not rock on its springs.
            const Tensor<1, dim> slip = relative - approach * n;
            Tensor<1, dim> u = Fields::vector<dim>(q + spring) + dt * slip;
            u -= (u * n) * n;
            Tensor<1, dim> tangential = -k * u - damping * slip;
            if (tangential.norm() > mu * normal_force)
              {
                // Sliding: the Coulomb force, and the spring that carries it.
                tangential *= mu * normal_force / tangential.norm();
                u = -tangential / k;
              }
            f += tangential;
            for (unsigned int d = 0; d < dim; ++d)
              q[spring + d] = u[d];
          }
        for (unsigned int d = 0; d < dim; ++d)
          load[d] += f[d];
        reaction -= dt * f;
      }
    this->add_impulse(reaction);
  }


  template <int dim>
  double
  RigidWall<dim>::put_back(Particles::ParticleAccessor<dim> &p,
                           const FieldLayout                &l,
                           const Point<dim>                 &position,
                           Tensor<1, dim>                   &reaction,
                           double                           &work) const
  {
    const Tensor<1, dim> &n       = prm.normal;
    const double          overlap = -((p.get_location() - position) * n);
    // Most points are in front: no root for them.
    if (!(overlap > 0))
      return 0;
    double      *q     = p.get_properties().data();
    const double depth = 0.25 * std::pow(q[l.volume], 1. / dim);
    if (!(overlap > depth))
      return 0;
    p.set_location(p.get_location() + (overlap - depth) * n);
    const Tensor<1, dim> v   = Fields::vector<dim>(q + l.velocity);
    const double         lag = prm.velocity * n - v * n;
    if (lag > 0)
      {
        const Tensor<1, dim> v_new = v + lag * n;
        Fields::store(v_new, q + l.velocity);
        reaction -= q[l.mass] * lag * n;
        work += 0.5 * q[l.mass] * (v_new.norm_square() - v.norm_square());
      }
    return overlap - depth;
  }


  template struct RigidWallParameters<1>;
  template struct RigidWallParameters<2>;
  template struct RigidWallParameters<3>;
  template class RigidWall<1>;
  template class RigidWall<2>;
  template class RigidWall<3>;
} // namespace mpm
