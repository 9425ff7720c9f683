// The loads of the step and the work done on the bodies from outside: the
// point loads (pressure and traction on a loaded surface, the rigid walls'
// penalty forces), the body forces, the rigid walls putting back the points
// behind them, and the account of their work that the energy guard reads.
// The scatter adds the loads to the nodal forces; the velocity region,
// contact with rigid bodies and the virtual fluid add their work where
// they act on the grid.
#include <mpm/external_loads.h>

#include <cmath>
#include <sstream>
#include <vector>

namespace mpm
{
  template <int dim>
  ExternalLoads<dim>::ExternalLoads(
    const StepParts<dim>      &parts,
    const std::vector<double> &wave_modulus_of_body)
    : points(parts.points)
    , rigid_walls(parts.rigid_walls)
    , wave_modulus_of_body(wave_modulus_of_body)
    , context(parts.context)
    , account(parts.work)
  {
    for (const auto &body : points.bodies())
      {
        body_forces.push_back(body.body_force.get());
        pressures.push_back(body.pressure.get());
        tractions.push_back(body.traction.get());
        with_body_forces = with_body_forces || body.body_force;
      }
  }


  template <int dim>
  void
  ExternalLoads<dim>::set_body_force_time(const double t)
  {
    for (auto *f : body_forces)
      if (f != nullptr)
        f->set_time(t);
  }


  template <int dim>
  void
  ExternalLoads<dim>::keep_points_in_front_of_rigid_walls(const double t)
  {
    const unsigned int n_walls = rigid_walls.size();
    if (n_walls == 0)
      return;
    std::vector<Point<dim>>     position(n_walls);
    std::vector<Tensor<1, dim>> reaction(n_walls);
    std::vector<double>         work_of_wall(n_walls, 0.);
    for (unsigned int w = 0; w < n_walls; ++w)
      position[w] = rigid_walls[w]->position(t);
    // A point put back by one wall may then be behind another. In a corner
    // a few more passes settle it (alternating projections onto the walls'
    // half-spaces converge there: in a 53-degree notch by 0.36 a pass);
    // between walls that close on each other faster than the material can
    // flow away, or meet, nothing does, and the run stops rather than pack
    // points without deforming them (issue 32: two walls at 10 m/s on the
    // soft disks squeezed both into a sheet and ran on through each other).
    const unsigned int max_passes = n_walls == 1 ? 1 : 40;
    const FieldLayout &l          = points.layout();
    for (auto &p : points.handler())
      {
        double moved = 0;
        for (unsigned int pass = 0; pass < max_passes; ++pass)
          {
            moved = 0;
            for (unsigned int w = 0; w < n_walls; ++w)
              moved += rigid_walls[w]->put_back(
                p, l, position[w], reaction[w], work_of_wall[w]);
            if (moved == 0)
              break;
          }
        if (n_walls == 1 || moved == 0 || context.failed())
          continue;
        const double size = std::pow(p.get_properties()[l.volume], 1. / dim);
        if (moved > 1e-6 * size)
          {
            std::ostringstream msg;
            // The walls' time t (the end of the step), not the step's start
            // that StepContext::when() names.
            msg << "step " << context.n_steps << ", t = " << t
                << ": material point " << p.get_id() << " of body "
                << p.get_properties()[l.body] << " at (" << p.get_location()
                << ") is pinched between rigid walls: put back by each in "
                << "turn " << max_passes << " times, it still lies more than "
                << "a quarter of its size (" << 0.25 * size
                << " m) behind one of them; the walls close on the material "
                   "faster than it can flow away, or meet";
            context.fail(msg.str());
          }
      }
    for (unsigned int w = 0; w < n_walls; ++w)
      {
        rigid_walls[w]->add_impulse(reaction[w]);
        account.external += work_of_wall[w];
        account.absolute_external += std::abs(work_of_wall[w]);
      }
    // One wall puts every point back in one pass: no pinch to agree on.
    if (n_walls > 1)
      context.raise_if_failed();
  }


  template <int dim>
  void
  ExternalLoads<dim>::make_point_loads(const double dt)
  {
    const FieldLayout &l = points.layout();
    for (const auto &loads : {pressures, tractions})
      for (auto *f : loads)
        if (f != nullptr)
          f->set_time(context.t);
    for (auto &p : points.handler())
      {
        double *q = p.get_properties().data();
        Fields::store(Tensor<1, dim>(), q + l.point_load);
        if (l.surface_area == FieldLayout::absent)
          continue;
        const bool with_moment = l.load_moment != FieldLayout::absent;
        if (with_moment)
          Fields::store(Tensor<2, dim>(), q + l.load_moment);
        const unsigned int b = q[l.body];
        if (pressures[b] == nullptr && tractions[b] == nullptr)
          continue;
        // Most points of a loaded body lie inside it: skip the parsers.
        const Tensor<1, dim> area = Fields::vector<dim>(q + l.surface_area);
        if (area.norm_square() == 0)
          continue;
        Tensor<1, dim> load;
        if (pressures[b] != nullptr)
          {
            const double pressure = pressures[b]->value(p.get_location());
            check_load(std::abs(pressure), b, "pressure", p.get_location());
            load -= pressure * area;
          }
        if (tractions[b] != nullptr)
          {
            Tensor<1, dim> traction;
            for (unsigned int d = 0; d < dim; ++d)
              traction[d] = tractions[b]->value(p.get_location(), d);
            check_load(traction.norm(), b, "traction", p.get_location());
            load += traction * area.norm();
          }
        Fields::store(load, q + l.point_load);
        if (with_moment)
          Fields::store(
            outer_product(load, Fields::vector<dim>(q + l.surface_offset)),
            q + l.load_moment);
      }
    for (auto *wall : rigid_walls)
      wall->act_on_points(
        points.handler(), l, wave_modulus_of_body, context.t, dt);
    add_point_load_work(0.5 * dt);
  }


  /**
   * End the step's account of external work: the second halves of the
   * trapezoidal rules (point loads and body forces at the new velocities;
   * the first halves were taken at the start), then the totals. Extra
   * passes over the points only in scenes with such loads.
   */
  template <int dim>
  void
  ExternalLoads<dim>::close_step(const double dt)
  {
    const FieldLayout &l = points.layout();
    if (l.point_load != FieldLayout::absent)
      add_point_load_work(0.5 * dt);
    if (with_body_forces)
      {
        TimerOutput::Scope scope(context.timer, "external work");
        set_body_force_time(context.t + dt);
        for (const auto &p : points.handler())
          {
            const double *q = p.get_properties().data();
            body_force_power +=
              q[l.mass] * (body_force(q) * Fields::vector<dim>(q + l.velocity));
          }
      }
    step_work += 0.5 * dt * body_force_power;
    account.external += step_work;
    account.absolute_external += std::abs(step_work);
    step_work        = 0;
    body_force_power = 0;
  }


  /**
   * The work of the point loads (surface loads, penalty walls) over the
   * step, by the trapezoidal rule: half of it at the points' velocities
   * before the step, half after. At the start velocity alone, a load
   * applied to a body at rest did no work in its first step, and the
   * energy guard stopped a loaded column at t = 1e-4 (found by the fuzzer).
   */
  template <int dim>
  void
  ExternalLoads<dim>::add_point_load_work(const double weight)
  {
    TimerOutput::Scope scope(context.timer, "external work");
    const FieldLayout &l = points.layout();
    // A surface load acts at the surface, d from the point, where the
    // velocity is v + L d: its power is F . v + (F (x) d) : L.
    const bool at_surface = l.load_moment != FieldLayout::absent;
    for (const auto &p : points.handler())
      {
        const double *q     = p.get_properties().data();
        double        power = Fields::vector<dim>(q + l.point_load) *
                       Fields::vector<dim>(q + l.velocity);
        if (at_surface)
          power += scalar_product(Fields::tensor<dim>(q + l.load_moment),
                                  Fields::tensor<dim>(q + l.velocity_gradient));
        step_work += weight * power;
      }
  }


  template class ExternalLoads<1>;
  template class ExternalLoads<2>;
  template class ExternalLoads<3>;
} // namespace mpm
