#ifndef mpm_transfer_grid_to_particle_h
#define mpm_transfer_grid_to_particle_h

#include <mpm/grid/nodal_state.h>
#include <mpm/integrator_parameters.h>
#include <mpm/material_points.h>
#include <mpm/step_parts.h>
#include <mpm/transfer/point_loop.h>

#include <string>

namespace mpm
{
  using namespace dealii;

  /**
   * The transfer back to the points (G2P): their velocities by the scene's
   * transfer (transfer/flip_pic.h, transfer/apic.h), their positions, and
   * their kinematics: the strain rate L (transfer/strain_rate.h), the
   * volume and F from I + dt L. A point that would invert is the step's
   * failure, with its diagnosis. The loops are templates on the basis,
   * instantiated for each in grid_to_particle.cc.
   */
  template <int dim>
  class GridToParticle
  {
  public:
    /// @p guard_mass: the small-mass guard's nodal mass.
    GridToParticle(const StepParts<dim> &parts, const double guard_mass);

    /// Velocities and positions from the grid velocities of a step of
    /// @p dt, and with @p kinematics the strain rate from the
    /// force-updated ones (USL).
    template <typename Basis>
    void
    gather(const Basis &basis, const double dt, const bool kinematics);

    /// The strain rate from the nodal velocities in @p slot, and volume
    /// and F over @p dt (USF, MUSL).
    template <typename Basis>
    void
    update_kinematics(const Basis       &basis,
                      const double       dt,
                      const unsigned int slot);

  private:
    using Layout = NodalLayout<dim>;

    /// Store L, update volume and F by I + dt L; note a failure if the
    /// point would invert.
    template <typename Iterator>
    void
    apply_velocity_gradient(const Iterator       &p,
                            double               *q,
                            const Tensor<2, dim> &L,
                            const double          dt);

    /**
     * A parted point (the caller checks its opening) alone near a fixed or
     * friction face forgets the part of its affine field that varies along
     * the face's normal (see the definition for why): C_p e_n = 0.
     */
    template <typename Stencil>
    void
    release_lone_point_at_rough_face(const Point<dim>  &x,
                                     const Stencil     &s,
                                     const double      *u,
                                     const unsigned int stride,
                                     double            *q) const;

    /// A fixed or friction face: its normal's axis, where it lies, and how
    /// far from it a point's stencil reaches its nodes.
    struct RoughFace
    {
      unsigned int axis;
      double       coordinate;
      double       reach;
    };
    std::vector<RoughFace> rough_faces;

    const IntegratorParameters<dim> &prm;
    MaterialPoints<dim>             &points;
    const PointLoop<dim>            &loop;
    const NodalState<dim>           &nodes;
    const double                     guard_mass;
    StepContext                     &context;
  };
} // namespace mpm

#endif
