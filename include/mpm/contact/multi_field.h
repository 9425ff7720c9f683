#ifndef mpm_contact_multi_field_h
#define mpm_contact_multi_field_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <mpm/boundary_conditions/reaction_meter.h>
#include <mpm/material_points.h>

#include <memory>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /// Which bodies get a velocity field of their own on the grid, and the
  /// Coulomb friction between fields.
  template <int dim>
  struct ContactParameters
  {
    static void
    declare_parameters(ParameterHandler &prm);
    /// @p n_bodies checks the body list.
    void
    parse_parameters(ParameterHandler &prm, const unsigned int n_bodies);

    std::vector<bool> own_field; ///< per body (rigid bodies added later)
    double            friction_coefficient = 0;
  };


  /**
   * Multi-body contact on the grid (Bardenhagen et al. 2000, 2001): each
   * body that asks for it scatters into a velocity field of its own, the
   * others share field 0, and where two or more fields meet at a node their
   * velocities are corrected so that they do not interpenetrate:
   *
   *  - the normal of field f points out of f towards the others, from the
   *    mass gradients: n_f = (grad m_others - grad m_f) / |...| (so two
   *    fields get opposite normals and momentum is conserved);
   *  - a field approaching the centre-of-mass velocity v_cm of the node,
   *    (v_f - v_cm) . n_f > 0, loses that normal part, and its tangential
   *    relative velocity is cut by at most mu times the normal part removed
   *    (Coulomb), never reversed; a field moving away is left alone (free
   *    separation);
   *  - a rigid field acts only at the nodes inside its body (in the domain
   *    of one of its points, a box of side V^(1/dim)): every stencil
   *    carries its field beyond its surface, a node row into the body it
   *    presses with B-splines (a footing pushing one row deep in the soil:
   *    +41 % bearing pressure), and a threshold on its share of a node
   *    instead lets contact drop out as the body crosses node rows.
   *    Deformable fields touch wherever they share a node, as in
   *    Bardenhagen's algorithm.
   *
   * A rigid body is a field whose velocity is prescribed, v_R(t): it is set
   * on the field's nodes, and at a node it shares it replaces v_cm (its mass
   * is taken as infinite). The momentum it removes from the other fields
   * is its force on the material (statistics: rigid<b>_force_x, ...).
   */
  template <int dim>
  class MultiFieldContact : public ForceReporter
  {
  public:
    MultiFieldContact(const ContactParameters<dim>           &parameters,
                      const std::vector<BodyParameters<dim>> &bodies);

    /// The contact data per node and field (see correct_node): sum_p m_p
    /// grad phi_I(x_p) (dim) and the number of the field's points whose
    /// domain holds the node (1).
    static constexpr unsigned int data_per_field = dim + 1;

    /// 1 if no body has a field of its own (the single-field scheme).
    unsigned int
    n_fields() const
    {
      return field_count;
    }

    /// Whether two deformable fields may meet: bodies of different fields,
    /// neither rigid.
    bool
    deformable_bodies_touch() const
    {
      return n_deformable_fields > 1;
    }

    unsigned int
    field_of_body(const unsigned int body) const
    {
      return body_field[body];
    }

    /// Is field @p f a rigid body's (its velocity prescribed)?
    bool
    is_rigid_field(const unsigned int f) const
    {
      return rigid_of_field[f] >= 0;
    }

    void
    set_time(const double t);

    /**
     * Set the rigid fields' velocities and correct the others at one node.
     * @p node points at the node's first field; field f's mass is at
     * node[f * stride] and its velocity at node[f * stride + slot];
     * @p data holds each field's sum_p m_p grad phi_I(x_p) (dim) and the
     * number of its points whose domain holds the node (1). A deformable
     * field lighter than @p min_mass (the integrator's small nodal mass)
     * moves with the reference velocity along the normal, and so do all
     * deformable fields if @p hold_normal. The momentum the rigid fields
     * remove is added to @p rigid_impulse (one per rigid body, per unit
     * dt: the caller scales it). Returns whether a deformable field
     * approached the others or a rigid body here (was pressed on them).
     */
    bool
    correct_node(double                      *node,
                 const unsigned int           stride,
                 const unsigned int           slot,
                 const double                *data,
                 const double                 min_mass,
                 const bool                   hold_normal,
                 std::vector<Tensor<1, dim>> &rigid_impulse) const;

    /// Rigid velocities only (a node with one field).
    void
    set_rigid_velocities(double            *node,
                         const unsigned int stride,
                         const unsigned int slot) const;

    /// The rigid bodies, in the order of rigid_impulse.
    const std::vector<unsigned int> &
    rigid_bodies() const
    {
      return rigid_body_list;
    }

    /// Velocity of rigid body @p r (in the order of rigid_bodies()) at the
    /// time of the last set_time().
    const Tensor<1, dim> &
    rigid_velocity_of(const unsigned int r) const
    {
      return current_rigid_velocity[r];
    }

    void
    add_rigid_impulses(const std::vector<Tensor<1, dim>> &impulses);

    /// Statistics columns rigid<b>_force_x, ...
    std::vector<std::string>
    columns() const override;

    std::vector<double>
    mean_force_since_last_call(const double time, MPI_Comm comm) override;

  private:
    const double              mu;
    unsigned int              field_count;
    unsigned int              n_deformable_fields; ///< with a body
    std::vector<unsigned int> body_field;
    std::vector<unsigned int> rigid_body_list;
    std::vector<int>          rigid_of_field; ///< -1: none
    std::vector<std::shared_ptr<FunctionParser<dim>>> rigid_velocity;
    std::vector<Tensor<1, dim>>                       current_rigid_velocity;
    std::vector<ReactionMeter<dim>>                   meters;
  };
} // namespace mpm

#endif
