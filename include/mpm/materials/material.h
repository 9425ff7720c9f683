#ifndef mpm_materials_material_h
#define mpm_materials_material_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <deal.II/particles/particle_handler.h>

#include <mpm/field_layout.h>

#include <memory>
#include <string>

namespace mpm
{
  using namespace dealii;

  /**
   * What a model is made for besides its own parameters: the body's
   * reference density, and the grid's cell size, the length over which a
   * softening model localises (its regularisation needs it).
   */
  struct MaterialContext
  {
    double density;
    /// The side of a square (cubic) cell of the grid cell's size; 0 where
    /// there is no grid (single-point drivers).
    double cell_size = 0.;
  };


  /**
   * A constitutive model: it turns the kinematics the integrator stores on
   * each material point (velocity gradient L, and F if the model asks for
   * it) into Cauchy stress, and owns whatever state it needs.
   *
   * The integrator calls update_stresses() once per body per step; the
   * model runs its own loop over the points, so there is one virtual call
   * per body and none per particle.
   *
   * In 1D and 2D every model is the 3D model restricted to uniaxial or plane
   * strain: the out-of-plane stretches are 1 and the out-of-plane stress is
   * whatever the model gives. The stored stress has the in-plane components
   * only; cauchy_stress_3d() gives all of them (output, pressure).
   */
  template <int dim>
  class Material
  {
  public:
    virtual ~Material() = default;

    /// Add the fields this model stores on every point to @p requests.
    virtual void
    request_fields(FieldRequests &requests) const = 0;

    /// Does the model store F (its stress follows from F, so it can start
    /// from an initial displacement)? Derived from request_fields.
    bool
    needs_deformation_gradient() const
    {
      FieldRequests requests;
      request_fields(requests);
      return requests.deformation_gradient;
    }

    /// Can the material part, returning to zero stress when pulled apart
    /// (a cohesionless flow: it stores an opening)? Derived from
    /// request_fields.
    bool
    can_part() const
    {
      FieldRequests requests;
      request_fields(requests);
      return requests.opening;
    }

    /**
     * Can the model change a point's volume other than elastically (plastic
     * dilatancy, a return to the apex of a pressure-dependent yield surface,
     * grains that part)? Then a point's J is a state of its own, not a
     * function of its pressure, and F-bar averages only each step's volume
     * change over a cell, not J itself (FBar::average_volume_change).
     */
    virtual bool
    volume_has_history() const
    {
      return false;
    }

    /// Can the model start from a given stress (initialise_point)?
    virtual bool
    accepts_initial_stress() const
    {
      return true;
    }

    /// Small-strain p-wave modulus lambda + 2 mu, for the CFL time step.
    virtual double
    p_wave_modulus() const = 0;

    /**
     * How the p-wave modulus grows with the point's pressure p, dM/dp: the
     * Tait fluid's tangent bulk modulus is K + gamma p, so a fluid held
     * under a pressure well above K (a soft fluid under its own weight)
     * carries waves far faster than sqrt(K / rho), and a time step from K
     * alone would be unstable. 0 for the models whose stiffness does not
     * depend on the pressure. The CFL time step uses M + slope max(p, 0).
     */
    virtual double
    wave_modulus_pressure_slope() const
    {
      return 0.;
    }

    /// The parameters that set the model's stiffness, as given, for
    /// messages (an initial stress the model cannot carry names them).
    virtual std::string
    stiffness_parameters() const
    {
      return "";
    }

    /// Small-strain shear modulus mu, for the s-wave impedance of
    /// absorbing faces.
    virtual double
    shear_modulus() const = 0;

    /**
     * Shear viscosity of a model whose stress is viscous in the current
     * strain rate (a fluid): the explicit step must then also resolve
     * momentum diffusion, dt < rho h^2 / (2 dim eta). 0 for the others (a
     * Maxwell solid's relaxation is integrated exactly and stays within
     * its elastic stiffness).
     */
    virtual double
    viscosity() const
    {
      return 0.;
    }

    /**
     * Does the stiffness act on the Kirchhoff stress (hyperelastic and
     * log-strain models: tau = J sigma)? Then the Cauchy stiffness is M / J
     * and the wave speed sqrt(M / rho0) at any J. Otherwise (a Cauchy stress
     * rate, the hypoelastic linear model) it is sqrt(M / rho) with the
     * current density rho = rho0 / J. The difference matters where points
     * spread apart (J >> 1: granular flow), where the hypoelastic estimate
     * would shrink the time step without need, and under strong compression.
     */
    virtual bool
    stiffness_is_kirchhoff() const
    {
      return false;
    }

    /**
     * Give a new point its initial state: the stress @p sigma0 (a full 3D
     * tensor; in 2D and 1D the out-of-plane normal components count) and
     * whatever state produces it. Throws a std::domain_error with the
     * reason if the model cannot hold that stress (outside the yield
     * surface); the caller names the parameter.
     */
    virtual void
    initialise_point(double                      *properties,
                     const FieldLayout           &layout,
                     const SymmetricTensor<2, 3> &sigma0) const;

    /// Update the stress of every locally owned point of body @p body.
    /// @p comm is for the models that look beyond a point (nonlocal
    /// damage); the pointwise ones ignore it.
    virtual void
    update_stresses(Particles::ParticleHandler<dim> &particles,
                    const FieldLayout               &layout,
                    const unsigned int               body,
                    const double                     dt,
                    const MPI_Comm                   comm) const = 0;

    /// The same for one point (tests, single-point drivers).
    virtual void
    update_point_stress(double            *properties,
                        const FieldLayout &layout,
                        const double       dt) const = 0;

    /// Stored (strain) energy of one point; used for statistics only.
    virtual double
    strain_energy(const double      *properties,
                  const FieldLayout &layout) const = 0;

    /// The full Cauchy stress of a point, out-of-plane components included.
    virtual SymmetricTensor<2, 3>
    cauchy_stress_3d(const double      *properties,
                     const FieldLayout &layout) const = 0;
  };


  /**
   * The registry: every model is known by the name a scene uses in
   * 'Body N/material', declares its parameters in a subsection of that name,
   * and is created from it. Adding a model is a line in
   * source/materials/registry.cc.
   */
  namespace MaterialRegistry
  {
    /// "linear elastic|neo-Hookean|...", for Patterns::Selection.
    std::string
    names();

    /// Declare every model's subsection inside the current subsection.
    void
    declare_parameters(ParameterHandler &prm);

    /// Create the model @p name from its subsection of the current
    /// subsection, for a body in @p context; @p path is used in error
    /// messages.
    template <int dim>
    std::unique_ptr<Material<dim>>
    create(const std::string     &name,
           ParameterHandler      &prm,
           const std::string     &path,
           const MaterialContext &context);
  } // namespace MaterialRegistry
} // namespace mpm

#endif
