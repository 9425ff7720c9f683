#ifndef mpm_verification_h
#define mpm_verification_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>

#include <array>

#include <mpm/checkpoint.h>
#include <mpm/material_points.h>
#include <mpm/statistics.h>

namespace mpm
{
  using namespace dealii;

  struct VerificationParameters
  {
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    enum class Exact
    {
      none,
      vibrating_bar,      ///< fixed-free bar, mode 1, body 0
      self_weight_column, ///< body 0 at rest under gravity, uniaxial stress
      displacement        ///< u(X, t) given as expressions, all bodies
    } exact;
    std::vector<std::string>      exact_displacement; ///< expressions
    std::map<std::string, double> constants;
    double                        amplitude;    ///< vibrating bar: v0
    double                        top_pressure; ///< self-weight column: p0
    double                        error_bound;  ///< 0: not checked
    double                        energy_change_bound;   ///< 0: not checked
    double                        momentum_change_bound; ///< 0: not checked
  };


  /**
   * Compares the run with what is known about it: an exact solution, and
   * the conservation of energy and momentum. The measured values become
   * columns of statistics.csv; check() turns a bound that was exceeded
   * into a failed run, which is how the tests assert accuracy.
   */
  template <int dim>
  class Verification
  {
  public:
    Verification(const VerificationParameters &parameters,
                 const MaterialPoints<dim>    &points,
                 const Tensor<1, dim>         &gravity,
                 MPI_Comm                      comm);

    /// Does the exact solution need the initial positions of the points?
    static bool
    needs_initial_position(const VerificationParameters &parameters);

    /// Names of the columns evaluate() returns.
    std::vector<std::string>
    columns() const;

    /// Measure the state at time @p t (collective).
    std::vector<double>
    evaluate(const Statistics<dim> &statistics, const double t);

    /// Throw RunError if a bound was exceeded; print what was measured.
    void
    check(ConditionalOStream &out) const;

    /// The maxima so far and the initial state, for a checkpoint.
    void
    save_state(RunState &state) const;
    void
    restore_state(const RunState &state);

  private:
    double
    exact_solution_error(const double t) const;
    /// L2 (sqrt of sum V |u - u_exact|^2) and max norm of the displacement
    /// error against the expression, over all points, and the L2 norm of
    /// the velocity error.
    std::array<double, 3>
    displacement_error(const double t) const;

    const VerificationParameters prm;
    const MaterialPoints<dim>   &points;
    const Tensor<1, dim>         gravity;
    MPI_Comm                     comm;

    std::unique_ptr<FunctionParser<dim>> exact_displacement;
    double                               max_error_max_norm = 0;
    double                               max_velocity_error = 0;
    bool                                 have_initial_state = false;
    double                               initial_energy, initial_momentum_scale;
    Tensor<1, dim>                       initial_momentum;
    double max_error = 0, last_error = 0, max_energy_change = 0,
           max_momentum_change = 0;
  };
} // namespace mpm

#endif
