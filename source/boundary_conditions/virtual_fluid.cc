#include <mpm/boundary_conditions/virtual_fluid.h>
#include <mpm/parameters.h>

namespace mpm
{
  template <int dim>
  void
  VirtualFluidParameters<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Boundary conditions");
    prm.enter_subsection("Virtual fluid");
    prm.declare_entry("enabled",
                      "false",
                      Patterns::Bool(),
                      "true or false: a fluid that is not resolved acts on "
                      "the free surface of the bodies it wets by its "
                      "pressure (the virtual stress method of cl-mpm): "
                      "buoyancy, water against a cliff, a pressure on a "
                      "surface that does not follow the grid. Its total "
                      "force on the bodies goes to statistics.csv "
                      "(fluid_force_x, ...).");
    prm.declare_entry("level",
                      "0",
                      Patterns::Anything(),
                      "Height of the fluid's free surface along the last "
                      "axis (y in 2D, z in 3D); below it the hydrostatic "
                      "pressure is density * |gravity| * (level - y).");
    prm.declare_entry("density",
                      "1000",
                      Patterns::Anything(),
                      "Density of the fluid in kg/m^3, >= 0 (0: no "
                      "hydrostatic pressure).");
    prm.declare_entry("pressure",
                      "0",
                      Patterns::Anything(),
                      "An extra pressure in Pa, added to the hydrostatic "
                      "one: an expression in x, y, z and t (e.g. a "
                      "uniform 'p0', or a ramp 'p0*t/T').");
    prm.declare_entry("bodies",
                      "",
                      Patterns::Anything(),
                      "The bodies the fluid wets, comma-separated indices; "
                      "empty: all.");
    prm.leave_subsection();
    prm.leave_subsection();
  }


  template <int dim>
  void
  VirtualFluidParameters<dim>::parse_parameters(ParameterHandler  &prm,
                                                const unsigned int n_bodies)
  {
    const std::string path = "Boundary conditions/Virtual fluid";
    constants              = Parse::constants(prm);
    prm.enter_subsection("Boundary conditions");
    prm.enter_subsection("Virtual fluid");
    enabled = prm.get_bool("enabled");
    if (enabled)
      {
        level    = Parse::bounded_double(prm, path, "level", -1e300, 1e300);
        density  = Parse::bounded_double(prm, path, "density", 0, 1e300);
        pressure = prm.get("pressure");
        // Parsed here so that a bad expression is an input error at once.
        Parse::vector_function<dim>({pressure}, constants, path + "/pressure");
        wets_body = Parse::body_flags(prm, path, "bodies", n_bodies, true);
      }
    prm.leave_subsection();
    prm.leave_subsection();
  }


  template <int dim>
  VirtualFluid<dim>::VirtualFluid(const VirtualFluidParameters<dim> &parameters,
                                  const double gravity_magnitude,
                                  const double cell_size)
    : MeteredReporter<dim>(parameters.enabled ? "fluid_force" : "")
    , prm(parameters)
    , g(gravity_magnitude)
  {
    if (prm.enabled && !Parse::is_zero({prm.pressure}))
      extra = Parse::vector_function<dim>({prm.pressure},
                                          prm.constants,
                                          "Boundary conditions/Virtual "
                                          "fluid/pressure",
                                          1e-3 * cell_size);
  }


  template <int dim>
  void
  VirtualFluid<dim>::set_time(const double t)
  {
    if (extra)
      extra->set_time(t);
  }


  template <int dim>
  double
  VirtualFluid<dim>::pressure(const Point<dim> &x,
                              Tensor<1, dim>   &gradient) const
  {
    gradient           = Tensor<1, dim>();
    double       p     = 0;
    const double depth = prm.level - x[dim - 1];
    if (depth > 0 && prm.density > 0)
      {
        p                 = prm.density * g * depth;
        gradient[dim - 1] = -prm.density * g;
      }
    if (extra)
      {
        p += extra->value(x);
        gradient += extra->gradient(x);
      }
    return p;
  }


  template struct VirtualFluidParameters<1>;
  template struct VirtualFluidParameters<2>;
  template struct VirtualFluidParameters<3>;
  template class VirtualFluid<1>;
  template class VirtualFluid<2>;
  template class VirtualFluid<3>;
} // namespace mpm
