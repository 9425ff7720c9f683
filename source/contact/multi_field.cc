#include <mpm/contact/multi_field.h>
#include <mpm/parameters.h>

#include <cmath>
#include <set>
#include <sstream>

namespace mpm
{
  template <int dim>
  void
  ContactParameters<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Contact");
    prm.declare_entry("bodies",
                      "",
                      Patterns::Anything(),
                      "Bodies with a velocity field of their own on the "
                      "grid (multi-body contact, Bardenhagen et al. 2000), "
                      "comma-separated indices; they touch, slide with "
                      "'friction coefficient' and separate freely. The "
                      "other bodies share one field, as with no contact. "
                      "Rigid bodies always have their own field. Empty: "
                      "none.");
    prm.declare_entry("friction coefficient",
                      "0",
                      Patterns::Anything(),
                      "Coulomb coefficient mu >= 0 between fields in "
                      "contact.");
    prm.leave_subsection();
  }


  template <int dim>
  void
  ContactParameters<dim>::parse_parameters(ParameterHandler  &prm,
                                           const unsigned int n_bodies)
  {
    prm.enter_subsection("Contact");
    own_field = Parse::body_flags(prm, "Contact", "bodies", n_bodies, false);
    friction_coefficient =
      Parse::bounded_double(prm, "Contact", "friction coefficient", 0, 1e300);
    prm.leave_subsection();
  }


  template <int dim>
  MultiFieldContact<dim>::MultiFieldContact(
    const ContactParameters<dim>           &parameters,
    const std::vector<BodyParameters<dim>> &bodies)
    : mu(parameters.friction_coefficient)
    , field_count(1)
    , body_field(bodies.size(), 0)
    , rigid_of_field(1, -1)
  {
    for (unsigned int b = 0; b < bodies.size(); ++b)
      if (parameters.own_field[b] || bodies[b].rigid_velocity)
        {
          body_field[b] = field_count++;
          rigid_of_field.push_back(-1);
          if (bodies[b].rigid_velocity)
            {
              rigid_of_field.back() = rigid_body_list.size();
              rigid_body_list.push_back(b);
              rigid_velocity.push_back(bodies[b].rigid_velocity);
            }
        }
    std::set<unsigned int> deformable;
    for (unsigned int b = 0; b < bodies.size(); ++b)
      if (!bodies[b].rigid_velocity)
        deformable.insert(body_field[b]);
    n_deformable_fields = deformable.size();
    current_rigid_velocity.resize(rigid_body_list.size());
    meters.resize(rigid_body_list.size());
    set_time(0);
  }


  template <int dim>
  void
  MultiFieldContact<dim>::set_time(const double t)
  {
    for (unsigned int r = 0; r < rigid_velocity.size(); ++r)
      {
        rigid_velocity[r]->set_time(t);
        for (unsigned int d = 0; d < dim; ++d)
          current_rigid_velocity[r][d] =
            rigid_velocity[r]->value(Point<dim>(), d);
        // The same on every rank (a function of t alone): no hang.
        if (!(current_rigid_velocity[r].norm() <= largest_input))
          {
            std::ostringstream s;
            s << "parameter 'Bodies/Body " << rigid_body_list[r]
              << "/rigid velocity' gives (" << current_rigid_velocity[r]
              << ") at t = " << t
              << ": a velocity must be finite and below 1e15 m/s";
            throw InputError(s.str());
          }
      }
  }


  template <int dim>
  void
  MultiFieldContact<dim>::set_rigid_velocities(double            *node,
                                               const unsigned int stride,
                                               const unsigned int slot) const
  {
    for (unsigned int f = 1; f < field_count; ++f)
      if (rigid_of_field[f] >= 0 && node[f * stride] > 0)
        for (unsigned int d = 0; d < dim; ++d)
          node[f * stride + slot + d] =
            current_rigid_velocity[rigid_of_field[f]][d];
  }


  template <int dim>
  bool
  MultiFieldContact<dim>::correct_node(
    double                      *node,
    const unsigned int           stride,
    const unsigned int           slot,
    const double                *data,
    const double                 min_mass,
    const bool                   hold_normal,
    std::vector<Tensor<1, dim>> &rigid_impulse) const
  {
    set_rigid_velocities(node, stride, slot);
    constexpr unsigned int data_stride = data_per_field;
    unsigned int           n_present   = 0;
    int                    rigid       = -1; // a rigid field here, if any
    double                 mass        = 0;
    Tensor<1, dim>         momentum, total_gradient;
    // A rigid field acts only at the nodes that lie in its body (in the
    // domain of one of its points): any stencil carries its field beyond
    // its surface, where it would push before the surfaces meet.
    auto takes_part = [&](const unsigned int f) {
      return node[f * stride] > 0 &&
             (rigid_of_field[f] < 0 || data[f * data_stride + dim] > 0);
    };
    for (unsigned int f = 0; f < field_count; ++f)
      {
        const double m = node[f * stride];
        if (!takes_part(f))
          continue;
        ++n_present;
        if (rigid_of_field[f] >= 0 && rigid < 0)
          rigid = f;
        mass += m;
        momentum += m * Fields::vector<dim>(node + f * stride + slot);
        total_gradient += Fields::vector<dim>(data + f * data_stride);
      }
    if (n_present < 2)
      return false;
    // The velocity the fields must not move into: a rigid body's, or the
    // centre of mass's.
    const Tensor<1, dim> reference =
      rigid >= 0 ? Fields::vector<dim>(node + rigid * stride + slot)
                 : momentum / mass;
    // Between deformable bodies, a field that only the edge of its
    // points' stencils reaches has a tiny mass but the full force of their
    // stress gradients, so its own normal velocity here is meaningless (it
    // grows as 1 / mass): where a field is that light, the fields do not
    // part along the normal (they still slide). Without this, two disks
    // with the linear basis and APIC gained up to 86 % energy where they
    // parted (their surfaces carry the contact stress; a free surface
    // carries none). Against a rigid body (its exact normal, no mass) it
    // is not needed, and it would hold a rolling disk where its surface
    // lifts off.
    // @p hold_normal (MUSL's strain-rate velocities where the fields pressed
    // on each other or on a rigid body at the step's force update, see
    // GridUpdate::apply_contact) has them stay together the same way, for
    // the strain rate only.
    bool keep_together = hold_normal;
    if (rigid < 0)
      for (unsigned int f = 0; f < field_count; ++f)
        keep_together =
          keep_together || (takes_part(f) && node[f * stride] < min_mass);
    bool pressed = false; // did a deformable field approach the others?
    for (unsigned int f = 0; f < field_count; ++f)
      {
        double *field = node + f * stride;
        if (!takes_part(f) || rigid_of_field[f] >= 0)
          continue;
        // gradients holds sum_p m_p grad phi_I(x_p) = -grad m at the node.
        // Against a rigid body its own normal is used: its shape is exact
        // and does not change, while the deformable body's mass gradient
        // tilts at the edges of the contact and would push it off.
        const Tensor<1, dim> own  = Fields::vector<dim>(data + f * data_stride);
        Tensor<1, dim>       n    = rigid >= 0
                                      ? -Fields::vector<dim>(data + rigid * data_stride)
                                      : own - (total_gradient - own);
        const double         norm = n.norm();
        if (!(norm > 0))
          continue;
        n /= norm;
        const Tensor<1, dim> v        = Fields::vector<dim>(field + slot);
        const Tensor<1, dim> relative = v - reference;
        const double         approach = relative * n;
        if (!(approach > 0) && !keep_together)
          continue;
        pressed                         = pressed || approach > 0;
        Tensor<1, dim>       change     = -approach * n;
        const Tensor<1, dim> tangential = relative - approach * n;
        const double         slide      = tangential.norm();
        if (slide > 0 && approach > 0)
          change -= std::min(1., mu * approach / slide) * tangential;
        Fields::store(Tensor<1, dim>(v + change), field + slot);
        if (rigid >= 0)
          rigid_impulse[rigid_of_field[rigid]] += field[0] * change;
      }
    return pressed;
  }


  template <int dim>
  void
  MultiFieldContact<dim>::add_rigid_impulses(
    const std::vector<Tensor<1, dim>> &impulses)
  {
    for (unsigned int r = 0; r < meters.size(); ++r)
      meters[r].add(impulses[r]);
  }


  template <int dim>
  std::vector<std::string>
  MultiFieldContact<dim>::columns() const
  {
    std::vector<std::string> c;
    for (const unsigned int b : rigid_body_list)
      for (const auto &name :
           ReactionMeter<dim>::columns("rigid" + std::to_string(b) + "_force"))
        c.push_back(name);
    return c;
  }


  template <int dim>
  std::vector<double>
  MultiFieldContact<dim>::mean_force_since_last_call(const double time,
                                                     MPI_Comm     comm)
  {
    std::vector<double> values;
    for (auto &meter : meters)
      for (const double f : meter.mean_since_last_call(time, comm))
        values.push_back(f);
    return values;
  }


  template struct ContactParameters<1>;
  template struct ContactParameters<2>;
  template struct ContactParameters<3>;
  template class MultiFieldContact<1>;
  template class MultiFieldContact<2>;
  template class MultiFieldContact<3>;
} // namespace mpm
