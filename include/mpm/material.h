#ifndef mpm_material_h
#define mpm_material_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/particles/particle_handler.h>

#include <mpm/field_layout.h>

#include <memory>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * A constitutive model: it turns the kinematics the integrator stores on
   * each material point (velocity gradient L, and F if the model asks for
   * it) into Cauchy stress, and owns whatever state it needs.
   *
   * The integrator calls update_stresses() once per body per step; the
   * model runs its own loop over the points, so there is one virtual call
   * per body and none per particle.
   */
  template <int dim>
  class Material
  {
  public:
    virtual ~Material() = default;

    /// Does the model need the deformation gradient stored on each point?
    virtual bool
    needs_deformation_gradient() const = 0;

    /// Small-strain p-wave modulus lambda + 2 mu, for the CFL time step.
    virtual double
    p_wave_modulus() const = 0;

    /// Update the stress of every locally owned point of body @p body.
    virtual void
    update_stresses(Particles::ParticleHandler<dim> &particles,
                    const FieldLayout               &layout,
                    const unsigned int               body,
                    const double                     dt) const = 0;

    /// Stored (strain) energy of one point; used for statistics only.
    virtual double
    strain_energy(const double      *properties,
                  const FieldLayout &layout) const = 0;
  };


  /**
   * The registry: every model is known by the name a scene uses in
   * 'Body N/material', declares its parameters in a subsection of that name,
   * and is created from it. Adding a model is a line in material.cc.
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
    /// subsection; @p path is used in error messages.
    template <int dim>
    std::unique_ptr<Material<dim>>
    create(const std::string &name,
           ParameterHandler  &prm,
           const std::string &path);
  } // namespace MaterialRegistry
} // namespace mpm

#endif
