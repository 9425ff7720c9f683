#ifndef mpm_boundary_conditions_virtual_fluid_h
#define mpm_boundary_conditions_virtual_fluid_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <mpm/boundary_conditions/reaction_meter.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /// A fluid that is not resolved: its pressure acts on the free surface of
  /// the bodies it wets (water against an ice cliff, a floating block, a
  /// pressure on a surface that does not follow the grid).
  template <int dim>
  struct VirtualFluidParameters
  {
    static void
    declare_parameters(ParameterHandler &prm);
    /// @p n_bodies checks the body list.
    void
    parse_parameters(ParameterHandler &prm, const unsigned int n_bodies);

    bool        enabled = false;
    double      level   = 0; ///< free surface, along the last axis
    double      density = 0; ///< of the fluid: hydrostatic part
    std::string pressure;    ///< an extra p(x, t), "0" if none
    std::map<std::string, double> constants;
    std::vector<bool>             wets_body; ///< per body
  };


  /**
   * The pressure of the fluid, p(x, t) = rho_f |g| max(0, level - x_up) +
   * p_extra(x, t) (x_up: the last coordinate), and its gradient; the
   * virtual stress method (cl-mpm; see ParticleToGrid::add_fluid_forces)
   * turns it into nodal forces on the wetted surface. The total force the
   * fluid exerts on the bodies is measured like a reaction (statistics
   * columns fluid_force_x, ...): its vertical part is the buoyancy.
   */
  template <int dim>
  class VirtualFluid : public MeteredReporter<dim>
  {
  public:
    VirtualFluid(const VirtualFluidParameters<dim> &parameters,
                 const double                       gravity_magnitude,
                 const double                       cell_size);

    bool
    enabled() const
    {
      return prm.enabled;
    }

    bool
    wets(const unsigned int body) const
    {
      return prm.wets_body[body];
    }

    void
    set_time(const double t);

    /// p at @p x; its gradient goes to @p gradient.
    double
    pressure(const Point<dim> &x, Tensor<1, dim> &gradient) const;

  private:
    const VirtualFluidParameters<dim>    prm;
    const double                         g;
    std::unique_ptr<FunctionParser<dim>> extra; ///< null if none
  };
} // namespace mpm

#endif
