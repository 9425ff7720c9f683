#ifndef mpm_materials_pointwise_h
#define mpm_materials_pointwise_h

// What the models in source/materials/ share: the loop over a body's points,
// the elastic constants, and how a model is declared and created. Included
// by the model sources only, not by the rest of the program.

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <mpm/materials/material.h>
#include <mpm/parameters.h>

#include <memory>
#include <string>

namespace mpm
{
  /**
   * The loop every pointwise model shares: visit the points of one body
   * and apply Law::update_point, inlined, to each (CRTP: no virtual call per
   * point).
   */
  template <int dim, typename Law>
  class PointwiseMaterial : public Material<dim>
  {
  public:
    void
    update_stresses(Particles::ParticleHandler<dim> &particles,
                    const FieldLayout               &layout,
                    const unsigned int               body,
                    const double                     dt,
                    const MPI_Comm) const override
    {
      const Law   &law = static_cast<const Law &>(*this);
      const double id  = body;
      for (auto &particle : particles)
        {
          double *p = particle.get_properties().data();
          if (p[layout.body] == id)
            law.update_point(p, layout, dt);
        }
    }

    void
    update_point_stress(double            *properties,
                        const FieldLayout &layout,
                        const double       dt) const override
    {
      static_cast<const Law &>(*this).update_point(properties, layout, dt);
    }
  };


  /// Isotropic elastic constants from E and nu, read and checked in one
  /// place.
  struct ElasticConstants
  {
    ElasticConstants(ParameterHandler &prm, const std::string &path);

    static void
    declare(ParameterHandler &prm);

    double lambda;
    double mu;
    /// E and nu as the scene gives them, with their full names.
    std::string given;

    double
    bulk_modulus() const
    {
      return lambda + 2. / 3. * mu;
    }

    double
    youngs_modulus() const
    {
      return mu * (3. * lambda + 2. * mu) / (lambda + mu);
    }
  };


  /**
   * A pointwise model of isotropic ElasticConstants: what the program asks
   * of its stiffness (the P-wave and shear moduli, the constants as the
   * scene gave them) answered in one place for every such model.
   */
  template <int dim, typename Law>
  class IsotropicPointwiseMaterial : public PointwiseMaterial<dim, Law>
  {
  public:
    /// The constants from the model's subsection at @p path (the registry
    /// passes the body's context too, which an elastic model does not
    /// need).
    IsotropicPointwiseMaterial(ParameterHandler  &prm,
                               const std::string &path,
                               const MaterialContext & = {0., 0.})
      : constants(prm, path)
    {
    }

    static void
    declare_parameters(ParameterHandler &prm)
    {
      ElasticConstants::declare(prm);
    }

    double
    p_wave_modulus() const override
    {
      return constants.lambda + 2. * constants.mu;
    }

    double
    shear_modulus() const override
    {
      return constants.mu;
    }

    std::string
    stiffness_parameters() const override
    {
      return constants.given;
    }

  protected:
    const ElasticConstants constants;
  };


  /// The current Jacobian J = V / V0 of a point, V0 = m / rho0.
  inline double
  jacobian(const double      *properties,
           const FieldLayout &layout,
           const double       reference_density)
  {
    return properties[layout.volume] * reference_density /
           properties[layout.mass];
  }


  /// How the registry makes a model: declare its parameters, create it.
  template <int dim>
  using MaterialCreator =
    std::unique_ptr<Material<dim>> (*)(ParameterHandler &,
                                       const std::string &,
                                       const MaterialContext &);

  template <int dim, template <int> class Model>
  std::unique_ptr<Material<dim>>
  make_material(ParameterHandler      &prm,
                const std::string     &path,
                const MaterialContext &context)
  {
    return std::make_unique<Model<dim>>(prm, path, context);
  }

  /// One line of the registry.
  struct MaterialEntry
  {
    const char *name;
    void (*declare)(ParameterHandler &);
    MaterialCreator<1> create_1d;
    MaterialCreator<2> create_2d;
    MaterialCreator<3> create_3d;
  };

  /// The entry of model @p Model under @p name.
  template <template <int> class Model>
  MaterialEntry
  material_entry(const char *name)
  {
    return {name,
            &Model<3>::declare_parameters,
            &make_material<1, Model>,
            &make_material<2, Model>,
            &make_material<3, Model>};
  }

  /// The entries of each family, defined in its source file.
  namespace Elastic
  {
    MaterialEntry
    linear_elastic();
    MaterialEntry
    neo_hookean();
  } // namespace Elastic
  namespace LogStrainModels
  {
    MaterialEntry
    hencky_elastic();
    MaterialEntry
    von_mises();
    MaterialEntry
    drucker_prager();
    MaterialEntry
    mohr_coulomb();
    MaterialEntry
    maxwell_viscoelastic();
  } // namespace LogStrainModels
  namespace Fluids
  {
    MaterialEntry
    newtonian_fluid();
  } // namespace Fluids
} // namespace mpm

#endif
