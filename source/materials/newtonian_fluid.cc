// A weakly compressible Newtonian fluid (water in dam breaks, sloshing,
// mud at high water content).
#include <mpm/materials/pointwise.h>

#include <cmath>
#include <stdexcept>

namespace mpm
{
  namespace
  {
    /**
     * sigma = -p(J) I + 2 eta D' with the Tait equation of state
     *   p = K / gamma (J^-gamma - 1),   J = V / V0 = rho0 / rho,
     * K the bulk modulus at rest (K = rho0 c^2, c the sound speed at rest)
     * and gamma the exponent (7 for water; 1 gives p = K (1/J - 1)).
     * The point stores nothing of its own: J follows from its volume, D'
     * from the velocity gradient of the step (the deviator of the 3D
     * stretching; in 2D and 1D the out-of-plane stretching is zero).
     *
     * A scene that models water chooses K so that c is ~10 times the
     * fastest flow (density changes ~1 %), as in weakly compressible SPH:
     * the time step follows c, not the real sound speed.
     */
    template <int dim>
    class NewtonianFluid : public PointwiseMaterial<dim, NewtonianFluid<dim>>
    {
    public:
      NewtonianFluid(ParameterHandler      &prm,
                     const std::string     &path,
                     const MaterialContext &context)
        : K(Parse::bounded_double(prm,
                                  path,
                                  "bulk modulus",
                                  0,
                                  largest_input,
                                  true))
        , gamma(Parse::bounded_double(prm, path, "Tait exponent", 1, 20))
        , eta(Parse::bounded_double(prm, path, "viscosity", 0, 1e300))
        , reference_density(context.density)
        , given(Parse::given(prm, path, "bulk modulus"))
      {
      }

      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("bulk modulus",
                          "2e6",
                          Patterns::Anything(),
                          "K in Pa, in (0, 1e15]: the bulk modulus at rest, "
                          "K = rho0 c^2 for sound speed c.");
        prm.declare_entry("Tait exponent",
                          "7",
                          Patterns::Anything(),
                          "gamma in [1, 20] of p = K/gamma (J^-gamma - 1) "
                          "(7: water).");
        prm.declare_entry("viscosity",
                          "1e-3",
                          Patterns::Anything(),
                          "Dynamic viscosity eta in Pa s, >= 0 (water: "
                          "1e-3).");
      }

      void
      request_fields(FieldRequests &) const override
      {
      }

      /// The bulk modulus at rest; under a pressure p the Tait fluid's
      /// tangent modulus is -J dp/dJ = K J^-gamma = K + gamma p (slope
      /// below), with the current density: c^2 = (K + gamma p) / rho.
      double
      p_wave_modulus() const override
      {
        return K;
      }

      double
      wave_modulus_pressure_slope() const override
      {
        return gamma;
      }

      std::string
      stiffness_parameters() const override
      {
        return given;
      }

      double
      shear_modulus() const override
      {
        return 0.;
      }

      double
      viscosity() const override
      {
        return eta;
      }

      /// A fluid at rest holds a pressure only: the point's density is set
      /// to the one the equation of state gives for it (its mass changes,
      /// its volume still tiles the body), so no pressure wave starts.
      void
      initialise_point(double                      *p,
                       const FieldLayout           &layout,
                       const SymmetricTensor<2, 3> &sigma0) const override
      {
        const double pressure = -trace(sigma0) / 3.;
        if (deviator(sigma0).norm() > 1e-10 * (std::abs(pressure) + 1.))
          throw std::domain_error(
            "carries shear stress, which is not a state at rest");
        const double base = 1. + gamma * pressure / K;
        if (!(base > 0))
          throw std::domain_error(
            "is a tension beyond the range (p > -K / gamma) of the equation "
            "of state");
        const double J = std::pow(base, -1. / gamma);
        p[layout.mass] = reference_density * p[layout.volume] / J;
        Fields::store(Fields::in_plane<dim>(sigma0), p + layout.stress);
      }

      inline void
      update_point(double *p, const FieldLayout &layout, const double) const
      {
        Fields::store(Fields::in_plane<dim>(stress(p, layout)),
                      p + layout.stress);
      }

      /// The energy stored by compression, -int_1^J p dJ per reference
      /// volume.
      double
      strain_energy(const double *p, const FieldLayout &layout) const override
      {
        const double J = jacobian(p, layout, reference_density);
        const double w =
          gamma == 1.
            ? -K * (std::log(J) - (J - 1.))
            : -K / gamma *
                ((std::pow(J, 1. - gamma) - 1.) / (1. - gamma) - (J - 1.));
        return w * p[layout.mass] / reference_density;
      }

      SymmetricTensor<2, 3>
      cauchy_stress_3d(const double      *p,
                       const FieldLayout &layout) const override
      {
        return stress(p, layout);
      }

    private:
      SymmetricTensor<2, 3>
      stress(const double *p, const FieldLayout &layout) const
      {
        const double         J = jacobian(p, layout, reference_density);
        const Tensor<2, dim> L =
          Fields::tensor<dim>(p + layout.velocity_gradient);
        SymmetricTensor<2, 3> D;
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = i; j < dim; ++j)
            D[i][j] = 0.5 * (L[i][j] + L[j][i]);
        const double pressure = K / gamma * (std::pow(J, -gamma) - 1.);
        return -pressure * unit_symmetric_tensor<3>() + 2. * eta * deviator(D);
      }

      const double      K, gamma, eta, reference_density;
      const std::string given;
    };
  } // namespace


  namespace Fluids
  {
    MaterialEntry
    newtonian_fluid()
    {
      return material_entry<NewtonianFluid>("Newtonian fluid");
    }
  } // namespace Fluids
} // namespace mpm
