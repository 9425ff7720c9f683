// F-bar: the volume change and the mean stress averaged over grid cells.
#include <mpm/bodies/body_parameters.h>
#include <mpm/transfer/deformation_increment.h>
#include <mpm/transfer/f_bar.h>

#include <cmath>

namespace mpm
{
  template <int dim>
  FBar<dim>::FBar(const BackgroundGrid<dim> &grid, MaterialPoints<dim> &points)
    : grid(grid)
    , points(points)
    , density_of_body(deformable_densities(points.bodies()))
  {
    for (const auto &body : points.bodies())
      by_increment.push_back(body.material->volume_has_history());
  }


  template <int dim>
  template <typename Add, typename Apply>
  void
  FBar<dim>::for_each_cell_bin(const Add &add, const Apply &apply)
  {
    const FieldLayout               &l         = points.layout();
    Particles::ParticleHandler<dim> &particles = points.handler();
    const unsigned int               n_bodies  = density_of_body.size();
    const unsigned int cells_of_tile = Utilities::pow(grid.tile_size(), dim);
    sums.resize(cells_of_tile * n_bodies);
    n_in_cell.resize(cells_of_tile);
    for (const unsigned int index : grid.locally_owned_tiles())
      {
        const auto        &tile = grid.tile(index);
        const unsigned int n    = particles.n_particles_in_cell(tile);
        if (n == 0)
          continue;
        std::fill(sums.begin(), sums.end(), std::array<double, 2>{});
        std::fill(n_in_cell.begin(), n_in_cell.end(), 0u);
        deformable.clear();
        const auto first = grid.first_cell_of_tile(index);
        auto       p     = particles.particles_in_cell(tile).begin();
        for (unsigned int i = 0; i < n; ++i, ++p)
          {
            typename BackgroundGrid<dim>::CellCoordinates cell;
            Point<dim>                                    xi;
            grid.cell_in_tile(first, p->get_reference_location(), cell, xi);
            unsigned int c = 0;
            for (int d = dim - 1; d >= 0; --d)
              c = c * grid.tile_size() + (cell[d] - first[d]);
            ++n_in_cell[c];
            double *const      q    = p->get_properties().data();
            const unsigned int body = static_cast<unsigned int>(q[l.body]);
            if (density_of_body[body] > 0) // not a rigid body
              {
                const unsigned int bin = c * n_bodies + body;
                deformable.push_back({q, bin, add(q, sums[bin])});
              }
          }
        for (const auto &[q, bin, own] : deformable)
          apply(q, sums[bin], own, n_in_cell[bin / n_bodies] > 1);
      }
  }


  /**
   * With the linear basis a cell's nodes can follow far fewer volume
   * changes than it holds points, so a nearly incompressible body locks:
   * each point's J is a constraint. F-bar (de Souza Neto et al. 1996; for
   * MPM Coombs et al. 2018) gives the points of a cell one volume change
   * and keeps each point's isochoric deformation: the step's increment
   * becomes dF_bar = (V / V_trial)^(1/dim) dF, V_trial the volume after the
   * kinematics and V the cell's share. The volume is conserved per cell,
   * and V, F and L stay consistent (V = V0 det F, I + dt L = dF_bar). In 2D
   * (plane strain) the exponent 1/2 acts in the plane, where all the volume
   * change happens. Which share depends on what the volume is:
   *
   * - Where the pressure is a function of J (elastic, fluid, von Mises
   *   and viscous flows, which keep the volume), every point takes its
   *   cell's J, V = V0_p sum V / sum V0: J is projected onto the cells,
   *   which takes out the pressure noise of points that arrive from other
   *   cells with their own J (tests/block_settling.prm at nu = 0.499, its
   *   points crossing cells as it settles: stress error 0.10 by J, 0.20 by
   *   increments; 1.37 without F-bar).
   * - Where the volume has a history (Material::volume_has_history: grains
   *   that parted at zero stress, a return to the apex, dilatancy), J is a
   *   state that the cell's J would overwrite: a point that enters another
   *   cell would take its J in one step. Loose and dense soil side by side
   *   differ by per cent, and a step of 5 % in J put 4.7 MPa of pressure
   *   on a point 1 m below a slope's crest (benchmarks/slope/README.md: the
   *   softening slide threw points metres up). There every point takes its
   *   cell's volume change over the step, V = V_p^n sum V_trial / sum V^n
   *   with V_p^n = V_trial / det(I + dt L) at the step's start: it keeps
   *   its own J, and only the step's rate is shared.
   */
  template <int dim>
  void
  FBar<dim>::average_volume_change(const double dt)
  {
    const FieldLayout &l = points.layout();
    // The volume the cell's average relates the point's to: at the step's
    // start, V_p / det(I + dt L_p), or the reference volume.
    const auto base_volume = [&](const double *q) {
      const unsigned int body = static_cast<unsigned int>(q[l.body]);
      if (!by_increment[body])
        return q[l.mass] / density_of_body[body];
      return q[l.volume] / determinant(deformation_increment(
                             Fields::tensor<dim>(q + l.velocity_gradient), dt));
    };
    for_each_cell_bin(
      [&](const double *q, std::array<double, 2> &bin) {
        const double base = base_volume(q);
        bin[0] += q[l.volume];
        bin[1] += base;
        return base;
      },
      [&](double                      *q,
          const std::array<double, 2> &bin,
          const double                 base,
          const bool                   shared) {
        // A point alone in its cell keeps its own volume change.
        if (!shared)
          return;
        const double V     = base * bin[0] / bin[1];
        const double ratio = V / q[l.volume];
        const double scale = dim == 1   ? ratio
                             : dim == 2 ? std::sqrt(ratio)
                                        : std::cbrt(ratio);
        // I + dt L_bar = scale (I + dt L).
        Tensor<2, dim> L = scale * Fields::tensor<dim>(q + l.velocity_gradient);
        for (unsigned int d = 0; d < dim; ++d)
          L[d][d] += (scale - 1.) / dt;
        Fields::store(L, q + l.velocity_gradient);
        q[l.volume] = V;
        if (l.deformation_gradient != FieldLayout::absent)
          Fields::store(Tensor<2, dim>(scale * Fields::tensor<dim>(
                                                 q + l.deformation_gradient)),
                        q + l.deformation_gradient);
      });
  }


  /**
   * The stress power with the averaged strain rate, sum_p V_p sigma_p :
   * L_bar_p, equals sum_p V_p sigma~_p : L_p, where sigma~_p is sigma_p with
   * its mean stress tr(sigma_p) / dim replaced by its cell's volume average
   * (to first order in dt: L_bar_p = L_p + (tr L_cell - tr L_p) I / dim).
   * So the internal force that is the adjoint of the averaged strain rate
   * takes sigma~_p; the work the grid does on the points is then the work
   * their stresses absorb. With each point's own stress it is not wherever
   * the mean stress varies within a cell: the difference, sum_p V_p (m_p -
   * m_cell)(tr L_p - tr L_cell), has no sign and fed the softening slope's
   * energy (benchmarks/slope/README.md). Where all points of a cell have
   * the same mean stress (an elastic body whose points share J) it is 0.
   */
  template <int dim>
  void
  FBar<dim>::average_mean_stress()
  {
    const FieldLayout &l           = points.layout();
    const auto         mean_stress = [&](const double *q) {
      return trace(Fields::symmetric<dim>(q + l.stress)) / dim;
    };
    for_each_cell_bin(
      [&](const double *q, std::array<double, 2> &bin) {
        const double m = mean_stress(q);
        bin[0] += q[l.volume] * m;
        bin[1] += q[l.volume];
        return m;
      },
      [&](double                      *q,
          const std::array<double, 2> &bin,
          const double                 m,
          const bool                   shared) {
        q[l.mean_stress_correction] = shared ? bin[0] / bin[1] - m : 0.;
      });
  }


  template class FBar<1>;
  template class FBar<2>;
  template class FBar<3>;
} // namespace mpm
