// What the unit tests that run the integrator share: the components it
// needs, made from a scene text, and the disk scene several of them use.
#ifndef mpm_tests_scene_h
#define mpm_tests_scene_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <mpm/simulation.h>

#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace tests
{
  using namespace dealii;

  /**
   * A 2D scene of one ball of radius @p radius at (0.5, 0.5), 2 x 2 points
   * per cell, in the unit square of @p cells x @p cells cells. The strings
   * are further lines of the subsections Simulation, Grid and Body 0.
   */
  inline std::string
  disk_scene(const unsigned int cells,
             const std::string &simulation = "",
             const std::string &grid       = "",
             const std::string &body       = "",
             const double       radius     = 0.3)
  {
    return "subsection Simulation\n  set dimension = 2\n" + simulation +
           "end\nsubsection Grid\n  set cells = " + std::to_string(cells) +
           "\n" + grid +
           "end\nsubsection Bodies\n  subsection Body 0\n"
           "    set shape = ball\n    set center = 0.5\n"
           "    set radius = " +
           std::to_string(radius) + "\n    set particles per cell = 2\n" +
           body + "  end\nend\n";
  }

  /// The components the integrator needs, made from a scene text.
  struct Scene
  {
    Scene(const std::string &text, const std::vector<std::string> &settings)
    {
      mpm::declare_scene_parameters(prm, 1);
      prm.parse_input_from_string(text);
      for (const auto &s : settings)
        {
          // "Section/entry=value"
          const auto slash = s.find('/'), equals = s.find('=');
          prm.enter_subsection(s.substr(0, slash));
          prm.set(s.substr(slash + 1, equals - slash - 1),
                  s.substr(equals + 1));
          prm.leave_subsection();
        }
      grid_parameters.parse_parameters(prm);
      integrator_parameters.parse_parameters(prm);
      bodies[0].parse_parameters(prm, 0, grid_parameters);
      grid   = std::make_unique<mpm::BackgroundGrid<2>>(grid_parameters, comm);
      points = std::make_unique<mpm::MaterialPoints<2>>(
        *grid,
        bodies,
        mpm::point_fields_needed(integrator_parameters, bodies),
        comm);
      points->generate();
      region = std::make_unique<mpm::VelocityRegion<2>>(
        mpm::VelocityRegionParameters<2>(), *grid);
      integrator = std::make_unique<mpm::TimeIntegrator<2>>(
        integrator_parameters, *grid, *points, *region, timer, comm);
    }

    const MPI_Comm                          comm = MPI_COMM_WORLD;
    ParameterHandler                        prm;
    mpm::GridParameters<2>                  grid_parameters;
    mpm::IntegratorParameters<2>            integrator_parameters;
    std::vector<mpm::BodyParameters<2>>     bodies{1};
    std::unique_ptr<mpm::BackgroundGrid<2>> grid;
    std::unique_ptr<mpm::MaterialPoints<2>> points;
    std::unique_ptr<mpm::VelocityRegion<2>> region;
    TimerOutput                             timer{comm,
                      std::cout,
                      TimerOutput::never,
                      TimerOutput::wall_times};
    std::unique_ptr<mpm::TimeIntegrator<2>> integrator;

    /// Visit each owned grid node with mass: f(position, local index).
    template <typename F>
    void
    for_each_node_with_mass(const F &f) const
    {
      const auto h = grid->cell_size();
      const auto n = grid_parameters.n_cells;
      for (unsigned int j = 0; j <= n[1]; ++j)
        for (unsigned int i = 0; i <= n[0]; ++i)
          {
            const Point<2> x =
              grid_parameters.lower_corner + Point<2>(i * h[0], j * h[1]);
            const Point<2> e(1e-9, 1e-9);
            for (const unsigned int k :
                 grid->owned_nodes_in_box(x + Tensor<1, 2>(-e),
                                          x + Tensor<1, 2>(e)))
              if (integrator->nodal_state().mass(k) > 0)
                f(x, k);
          }
    }

    Tensor<1, 2>
    nodal_velocity(const unsigned int k) const
    {
      return Tensor<1, 2>({integrator->nodal_state().velocity(k, 0),
                           integrator->nodal_state().velocity(k, 1)});
    }
  };


} // namespace tests

#endif
