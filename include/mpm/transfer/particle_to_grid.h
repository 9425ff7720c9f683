#ifndef mpm_transfer_particle_to_grid_h
#define mpm_transfer_particle_to_grid_h

#include <deal.II/lac/la_parallel_vector.h>

#include <mpm/background_grid.h>
#include <mpm/boundary_conditions/virtual_fluid.h>
#include <mpm/contact/multi_field.h>
#include <mpm/external_loads.h>
#include <mpm/grid/nodal_state.h>
#include <mpm/integrator_parameters.h>
#include <mpm/material_points.h>
#include <mpm/step_parts.h>
#include <mpm/transfer/f_bar.h>
#include <mpm/transfer/point_loop.h>

#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * The transfer to the grid (P2G): each point's mass, momentum (by the
   * scene's transfer: APIC gives a node its affine velocity field there)
   * and force (its stress with the current volume, gravity, body forces
   * and point loads) scattered to the nodes of its stencil into
   * NodalState::sums, summed over the ranks; with multi-body contact each
   * field's normals, and with a virtual fluid its forces on the wetted
   * surface. The loops are templates on the basis, instantiated for each
   * in particle_to_grid.cc, and compiled once per transfer.
   */
  template <int dim>
  class ParticleToGrid
  {
  public:
    /// The step's clock in @p context: body forces, the fluid's level.
    ParticleToGrid(const StepParts<dim> &parts, ExternalLoads<dim> &loads);

    /// After the grid's partition changed (the fluid's nodal volumes).
    void
    reinit();

    /**
     * Scatter the masses and momenta (@p mass_and_momentum) and the forces
     * (@p forces), each replacing what the nodal sums held. Nodes of mass
     * <= @p light_mass in NodalState::velocities are the small-mass
     * guard's light nodes: the internal force leaves them out as the
     * strain rate does (see particle_to_grid.cc).
     */
    template <typename Basis>
    void
    scatter(const Basis &basis,
            const bool   mass_and_momentum,
            const bool   forces,
            const double light_mass = 0.);

  private:
    using Layout = NodalLayout<dim>;

    /// The virtual stress method: the fluid's pressure on the wetted
    /// surface, as nodal forces added to the scattered ones.
    template <typename Basis>
    void
    add_fluid_forces(const Basis &basis);

    const IntegratorParameters<dim> &prm;
    const BackgroundGrid<dim>       &grid;
    MaterialPoints<dim>             &points;
    const PointLoop<dim>            &loop;
    NodalState<dim>                 &nodes;
    ExternalLoads<dim>              &loads;
    /// Null, or the multi-body contact (only if a body has its own field).
    MultiFieldContact<dim> *contact;
    /// Null, or a fluid acting on the bodies' surface (only if enabled).
    VirtualFluid<dim> *virtual_fluid;
    const StepContext &context;
    /// Each body's density, 0 for a rigid body (its contact normal is the
    /// gradient of its volume, not of its mass).
    std::vector<double> density_of_body;
    /// Virtual fluid only: the wetted bodies' volume at the nodes and the
    /// volume of a node's support in the grid (integral of its shape
    /// function).
    LinearAlgebra::distributed::Vector<double> fluid_volume, support_volume;
    /// F-bar's mean stress over cells, for the internal force.
    FBar<dim> cell_averages;
  };
} // namespace mpm

#endif
