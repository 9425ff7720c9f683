#ifndef mpm_boundary_conditions_rigid_wall_h
#define mpm_boundary_conditions_rigid_wall_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/particles/particle_handler.h>

#include <mpm/boundary_conditions/reaction_meter.h>
#include <mpm/field_layout.h>

#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /// A rigid plane at any angle to the grid (a point on it and its normal),
  /// moving at a constant velocity, with Coulomb friction. A scene has
  /// 'Boundary conditions/number of rigid walls' of them, in subsections
  /// 'Rigid wall 0', 'Rigid wall 1', ...
  template <int dim>
  struct RigidWallParameters
  {
    /// Declares subsection "Rigid wall <index>" of "Boundary conditions".
    static void
    declare_parameters(ParameterHandler &prm, const unsigned int index);
    void
    parse_parameters(ParameterHandler &prm, const unsigned int index);

    unsigned int   index = 0;
    Point<dim>     point;    ///< on the plane at t = 0
    Tensor<1, dim> normal;   ///< unit, pointing to the material's side
    Tensor<1, dim> velocity; ///< of the plane
    double         friction_coefficient = 0;
    double         penalty              = 1; ///< stiffness factor kappa
    double         damping_ratio        = 0.5;
  };


  /**
   * The wall acts on the material points by a penalty (cl-mpm's approach):
   * a point whose centre crosses the plane by delta is pushed back by
   * f_n = kappa M l^(dim-1) delta / h (l = V^(1/dim) the point's size, M
   * the body's p-wave modulus, h the cell size), damped in
   * the normal direction at a fraction of critical. Friction is a stick
   * spring of the same stiffness and damping on the tangential
   * displacement since the point touched (Cundall and Strack's contact),
   * limited to mu f_n: beyond it the point slides and the spring holds the
   * Coulomb force. A bare Coulomb force cannot hold a body at rest (it reverses
   * the velocity it stops), and capping it at the point's momentum lets a block
   * creep. With kappa = 1 the contact's frequency stays below the CFL step's
   * limit (omega dt <= CFL sqrt(2 kappa) < 2). The forces join the points'
   * external forces, so every basis and scheme sees the wall; their
   * reaction, summed between outputs, is the wall's mean force.
   *
   * Contact is at the points' centres, not at l/2 before them: the points
   * of a body filled on a lattice lie anywhere between 0 and l from a
   * surface that is not aligned with the grid, and a radius would start
   * some of them deep in the wall. The body's edge may thus sink up to
   * l/2 into the wall.
   */
  template <int dim>
  class RigidWall : public MeteredReporter<dim>
  {
  public:
    /// @p slip_slot: which of the points' stick springs this wall uses
    /// (walls with friction each have one; numbers::invalid_unsigned_int
    /// without friction).
    RigidWall(const RigidWallParameters<dim> &parameters,
              const double                    cell_size,
              const unsigned int              slip_slot);

    /**
     * Place the wall at time @p t and add, to each point's 'point load'
     * field, the wall's force on it over the step @p dt (nothing if not in
     * contact), updating its stick spring; the reaction joins the wall's
     * impulse. @p wave_modulus_of_body gives M per body.
     */
    void
    act_on_points(Particles::ParticleHandler<dim> &points,
                  const FieldLayout               &layout,
                  const std::vector<double>       &wave_modulus_of_body,
                  const double                     t,
                  const double                     dt);

    /**
     * The penalty lets a point into the wall by a fraction of its size; a
     * wall faster than the body's waves would push points through it (at
     * 10 m/s into the soft disks they fell 2.7 cm, half a cell, behind in
     * 5 steps). After the step's motion, with the wall at @p position, a
     * point @p p deeper than a quarter of its size (a penalty of M per
     * point size keeps a body resting under its weight far shallower: rho g
     * H h / M, 2e-5 m for a 1 m column of soil) is put back at that depth
     * and moves along the normal at least as fast as the wall; its momentum
     * change is added to @p reaction (the wall's impulse: add_impulse()) and
     * the kinetic energy it gains to @p work (for the energy balance).
     * Returns how far the point was moved (0 if it was not).
     */
    double
    put_back(Particles::ParticleAccessor<dim> &p,
             const FieldLayout                &layout,
             const Point<dim>                 &position,
             Tensor<1, dim>                   &reaction,
             double                           &work) const;

    /// Where the wall's point is at time @p t.
    Point<dim>
    position(const double t) const
    {
      return prm.point + t * prm.velocity;
    }

    /// The wall's speed: the time step must let no point cross it in a
    /// step (TimeIntegrator::stable_time_step).
    double
    speed() const
    {
      return prm.velocity.norm();
    }

  private:
    const RigidWallParameters<dim> prm;
    const double                   h;
    const unsigned int             slip_slot;
  };
} // namespace mpm

#endif
