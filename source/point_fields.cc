// Which point fields a scene needs: one function for the program and the
// unit tests.
#include <mpm/point_fields.h>
#include <mpm/transfer/transfers.h>

namespace mpm
{
  template <int dim>
  FieldRequests
  point_fields_needed(const IntegratorParameters<dim>             &integrator,
                      const std::vector<BodyParameters<dim>>      &bodies,
                      const std::vector<RigidWallParameters<dim>> &walls,
                      const bool initial_position,
                      const bool deformation_gradient)
  {
    FieldRequests fields;
    fields.initial_position = initial_position;
    for (const auto &body : bodies)
      fields.initial_position =
        fields.initial_position || body.body_force || body.is_displaced();
    fields.deformation_gradient =
      deformation_gradient || integrator.basis == BasisType::cpgimp;
    with_transfer(integrator.transfer, [&](auto transfer) {
      fields.affine_velocity = decltype(transfer)::stores_affine_velocity;
    });
    fields.macro_step             = integrator.macro_time_step > 0;
    fields.mean_stress_correction = integrator.f_bar;
    for (const auto &body : bodies)
      {
        fields.surface_area = fields.surface_area || body.has_surface_loads();
        fields.surface_offset =
          fields.surface_offset ||
          (body.has_surface_loads() &&
           body.loaded_face != numbers::invalid_unsigned_int);
      }
    for (const auto &wall : walls)
      fields.wall_slips += wall.friction_coefficient > 0;
    fields.point_load = fields.surface_area || !walls.empty();
    return fields;
  }


  template <int dim>
  std::vector<unsigned int>
  wall_slip_slots(const std::vector<RigidWallParameters<dim>> &walls)
  {
    std::vector<unsigned int> slots;
    unsigned int              n_slips = 0;
    for (const auto &wall : walls)
      slots.push_back(wall.friction_coefficient > 0
                        ? n_slips++
                        : numbers::invalid_unsigned_int);
    return slots;
  }


#define MPM_INSTANTIATE(dim)                               \
  template FieldRequests point_fields_needed<dim>(         \
    const IntegratorParameters<dim> &,                     \
    const std::vector<BodyParameters<dim>> &,              \
    const std::vector<RigidWallParameters<dim>> &,         \
    const bool,                                            \
    const bool);                                           \
  template std::vector<unsigned int> wall_slip_slots<dim>( \
    const std::vector<RigidWallParameters<dim>> &);
  MPM_INSTANTIATE(1)
  MPM_INSTANTIATE(2)
  MPM_INSTANTIATE(3)
#undef MPM_INSTANTIATE
} // namespace mpm
