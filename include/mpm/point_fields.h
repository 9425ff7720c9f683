#ifndef mpm_point_fields_h
#define mpm_point_fields_h

#include <mpm/bodies/body_parameters.h>
#include <mpm/boundary_conditions/rigid_wall.h>
#include <mpm/field_layout.h>
#include <mpm/integrator_parameters.h>

#include <vector>

namespace mpm
{
  /**
   * The point fields a scene needs beyond those every scene stores: what
   * its transfer, basis and macro step keep per point, what its bodies'
   * loads and body forces read, a stick spring per rigid wall with
   * friction, the initial position where @p initial_position (the
   * output of displacements, a verification) asks for it, and the
   * deformation gradient where @p deformation_gradient (the output of
   * strains) does. The program and
   * the unit tests lay out their points with it.
   */
  template <int dim>
  FieldRequests
  point_fields_needed(const IntegratorParameters<dim>             &integrator,
                      const std::vector<BodyParameters<dim>>      &bodies,
                      const std::vector<RigidWallParameters<dim>> &walls = {},
                      const bool initial_position     = false,
                      const bool deformation_gradient = false);

  /// The stick-spring slot of each rigid wall (the walls with friction,
  /// in order; numbers::invalid_unsigned_int for the others).
  template <int dim>
  std::vector<unsigned int>
  wall_slip_slots(const std::vector<RigidWallParameters<dim>> &walls);
} // namespace mpm

#endif
