#ifndef mpm_integrator_parameters_h
#define mpm_integrator_parameters_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <mpm/basis.h>
#include <mpm/material_points.h>
#include <mpm/options.h>
#include <mpm/transfer/transfers.h>

#include <cmath>
#include <string>

namespace mpm
{
  using namespace dealii;

  /// When the stress is updated within a step.
  enum class UpdateScheme
  {
    USL, ///< update stress last, from the new grid velocity
    USF, ///< update stress first, from the grid velocity before forces
    MUSL ///< USL with the updated particle momentum mapped back to the grid
  };

  /// The update schemes by their names ('Simulation/update scheme').
  inline const OptionTable<UpdateScheme> update_scheme_names = {
    {"USL", UpdateScheme::USL},
    {"USF", UpdateScheme::USF},
    {"MUSL", UpdateScheme::MUSL}};

  template <int dim>
  struct IntegratorParameters
  {
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
    /// The FLIP share alpha of a step of size @p dt: the FLIP fraction, or
    /// exp(-dt / PIC relaxation time), a share per second.
    double
    flip_fraction_of_step(const double dt) const
    {
      return pic_relaxation_time > 0 ? std::exp(-dt / pic_relaxation_time)
                                     : flip_fraction;
    }

    double          end_time;
    double          cfl_number;
    double          fixed_time_step; ///< 0: from the CFL condition
    UpdateScheme    scheme;
    BasisType       basis;
    Transfer        transfer;
    double          flip_fraction;       ///< alpha: 0 = PIC, 1 = FLIP
    double          pic_relaxation_time; ///< in s; 0: the FLIP fraction
    Tensor<1, dim>  gravity;
    double          damping;       ///< mass-proportional, in 1/s
    double          local_damping; ///< Cundall's alpha, in [0, 1)
    double          mass_scaling;  ///< inertia factor, >= 1
    double          small_mass_fraction;
    double          J_min, J_max; ///< run-health guard on V / V0
    bool            f_bar;        ///< volume change averaged over each cell
    double          energy_growth_bound; ///< run-health guard, 0: off
    bool            energy_residual;     ///< the step's energy residual
    OutOfGridPolicy out_of_grid;
    /// Substepping (seed 003): the macro step Dt, 0: off.
    double macro_time_step;
    /// Substeps per macro step, 0: as many as the CFL condition needs.
    unsigned int substeps;
    /// Macro-step operation: dynamic relaxation at kinetic energy peaks.
    bool kinetic_damping;
    /// The reconstruction: seed 003's closed form (APIC), or its
    /// least-squares system (4) solved with Trilinos.
    bool least_squares;
    /// lambda / h^2 of the least-squares system.
    double least_squares_weight;
    /// AMG (Trilinos ML) instead of Jacobi for its conjugate gradients.
    bool least_squares_amg;
    /// Newmark's gamma of the explicit (beta = 0) member; 1/2: central
    /// difference, the plain step.
    double newmark_gamma;
  };
} // namespace mpm

#endif
