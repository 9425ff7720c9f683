#ifndef mpm_boundary_conditions_velocity_region_h
#define mpm_boundary_conditions_velocity_region_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <mpm/background_grid.h>
#include <mpm/boundary_conditions/reaction_meter.h>

#include <array>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /// A box of grid nodes whose velocity is prescribed: a rigid footing, a
  /// plate, a piston pushed at constant speed into the material.
  template <int dim>
  struct VelocityRegionParameters
  {
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    bool       enabled = false;
    Point<dim> lower_corner, upper_corner;
    /// The corners as the scene gives them, for messages.
    std::string           lower_corner_text, upper_corner_text;
    Tensor<1, dim>        velocity;
    std::array<bool, dim> constrained; ///< per component; else free
  };


  /**
   * Enforces the prescribed velocity on the region's owned nodes, and
   * measures the force the region exerts on the material: at the force
   * update, a node whose unconstrained velocity would be v gets
   * m (v_prescribed - v) / dt from the region. The impulse is summed
   * between outputs, so the reported force is the mean over the output
   * interval (explicit MPM's nodal reaction is noisy from step to step).
   */
  template <int dim>
  class VelocityRegion : public MeteredReporter<dim>
  {
  public:
    VelocityRegion(const VelocityRegionParameters<dim> &parameters,
                   const BackgroundGrid<dim>           &grid);

    /// Find the region's owned nodes in @p grid (again, after the grid
    /// was repartitioned).
    void
    find_nodes(const BackgroundGrid<dim> &grid);

    bool
    enabled() const
    {
      return prm.enabled;
    }

    /// The speed it drives its nodes at (its constrained components; 0
    /// when disabled), for the time step.
    double
    speed() const
    {
      return prm.enabled ? prm.velocity.norm() : 0.;
    }

    /**
     * Set the velocity of the region's nodes in the interleaved nodal
     * array @p u (stride @p stride, mass at offset 0, velocity at
     * @p slot). If @p dt > 0 the change is the region's force over dt and
     * is added to the impulse. Returned is the work the region did,
     * m (v_region - v) . v_region summed over its nodes, at either update
     * (a constraint's force works at the velocity it imposes; a fixed
     * region does none).
     */
    double
    enforce(double            *u,
            const unsigned int stride,
            const unsigned int slot,
            const double       dt);

  private:
    const VelocityRegionParameters<dim> prm;
    std::vector<unsigned int>           nodes;
  };
} // namespace mpm

#endif
