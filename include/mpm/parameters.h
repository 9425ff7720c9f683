#ifndef mpm_parameters_h
#define mpm_parameters_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/base/function_parser.h>

#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * A user mistake in the scene: the message names the parameter, the value
   * and what is allowed. main() prints it on one line and exits non-zero,
   * without a stack trace.
   */
  class InputError : public std::runtime_error
  {
  public:
    InputError(const std::string &parameter,
               const std::string &value,
               const std::string &allowed);
    /// From a message already in that form (passed between ranks).
    explicit InputError(const std::string &message);
  };

  /**
   * A run that went wrong (instability, particle left the grid): the
   * message is the diagnosis. The last good output stays on disk.
   */
  class RunError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /**
   * The largest magnitude a number of the scene may have (in its SI unit:
   * m, m/s, m/s^2, Pa). Beyond it a value is a typo, and squares and
   * products of it overflow before a diagnosis could name it.
   */
  constexpr double largest_input = 1e15;

  /**
   * Collective failure: every rank calls this at the same point; if any
   * rank has a non-empty @p local_diagnosis, all ranks throw RunError with
   * the diagnosis of the lowest such rank (InputError if @p input_error).
   * A throw on one rank alone would leave the others waiting in the next
   * collective call.
   */
  void
  raise_if_any_failed(const std::string &local_diagnosis,
                      MPI_Comm           comm,
                      const bool         input_error = false);

  /**
   * k * @p interval, rounded to the double nearest its 15-digit decimal: the
   * output and checkpoint times land on the decimals a user writes. 6 *
   * 0.05 is 0.30000000000000004 in binary, and a run to 'end time = 0.3'
   * must end where a longer run writes that output, or a restart there
   * continues from a step that differs in the last bit.
   */
  double
  multiple_of(const double k, const double interval);

  /// The first multiple_of() @p interval after time @p t (a time that lies
  /// on a multiple, up to round-off, counts as reached): the next output
  /// or checkpoint time, counted from t = 0 whatever came before.
  double
  multiple_after(const double t, const double interval);

  /**
   * Helpers that read an entry of the current subsection of @p prm and
   * check it, so that every check produces the same kind of message. The
   * @p path is the subsection path used in messages ("Body 0/density").
   */
  namespace Parse
  {
    /// The number @p text spells (surrounding blanks allowed); throws
    /// std::invalid_argument if it is not one. Unlike deal.II's
    /// string_to_double, a number beyond the doubles is +-inf and one
    /// below them is its subnormal or 0 (the caller's range check then
    /// names it with its allowed range), not "not a number".
    double
    number(const std::string &text);

    /// Every entry @p prm declares, by its path ("Simulation/end time"),
    /// with its value as given (read off deal.II's own short listing).
    std::map<std::string, std::string>
    entries(const ParameterHandler &prm);

    /// Set the entry at @p path ("Bodies/Body 0/density") to @p value; an
    /// entry that is not declared or a value that does not fit its pattern
    /// is an InputError naming the path.
    void
    set_entry(ParameterHandler  &prm,
              const std::string &path,
              const std::string &value);

    /// "; did you mean 'A', 'B'?" with the (up to three) paths of
    /// @p declared closest to the misspelt @p path, or "" if none is
    /// close.
    std::string
    did_you_mean(const std::string                        &path,
                 const std::map<std::string, std::string> &declared);

    /// deal.II's own message for a malformed file or value, on one line.
    std::string
    one_line(const ExceptionBase &e);

    /// "'path/name' = 'text'": an entry as the scene gives it, for
    /// messages that name a parameter they did not read themselves.
    std::string
    given(const ParameterHandler &prm,
          const std::string      &path,
          const std::string      &name);

    /// A double that must lie in (lower, upper) or [lower, upper].
    double
    bounded_double(const ParameterHandler &prm,
                   const std::string      &path,
                   const std::string      &name,
                   const double            lower,
                   const double            upper,
                   const bool              lower_open = false,
                   const bool              upper_open = false);

    /// A comma-separated list of @p n doubles; a single value is taken for
    /// every component, an empty string as zero.
    std::vector<double>
    double_list(const ParameterHandler &prm,
                const std::string      &path,
                const std::string      &name,
                const unsigned int      n);

    template <int dim>
    Point<dim>
    point(const ParameterHandler &prm,
          const std::string      &path,
          const std::string      &name);

    template <int dim>
    Tensor<1, dim>
    vector(const ParameterHandler &prm,
           const std::string      &path,
           const std::string      &name);

    /// Expressions separated by ';' (deal.II FunctionParser syntax), one
    /// per component; a single expression is taken for every component and
    /// an empty string as zero.
    std::vector<std::string>
    expression_list(const ParameterHandler &prm,
                    const std::string      &name,
                    const unsigned int      n,
                    const std::string      &path);

    /// A comma-separated list of body indices in [0, n_bodies) as one flag
    /// per body; an empty list gives @p empty_means for every body.
    std::vector<bool>
    body_flags(const ParameterHandler &prm,
               const std::string      &path,
               const std::string      &name,
               const unsigned int      n_bodies,
               const bool              empty_means);

    /// True if every expression is the number zero.
    bool
    is_zero(const std::vector<std::string> &expressions);

    /// The scene's named constants, "name=value, ..." in
    /// 'Simulation/constants' (plus pi), for every expression.
    std::map<std::string, double>
    constants(ParameterHandler &prm);

    /// A vector function of x, y, z and t from @p expressions (one component
    /// each); an
    /// expression that does not parse is an InputError naming @p parameter.
    /// @p difference_step is the step of its finite-difference gradient.
    template <int dim>
    std::unique_ptr<FunctionParser<dim>>
    vector_function(const std::vector<std::string>      &expressions,
                    const std::map<std::string, double> &constants,
                    const std::string                   &parameter,
                    const double difference_step = 1e-8);
  } // namespace Parse
} // namespace mpm

#endif
