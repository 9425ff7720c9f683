#include <deal.II/base/mpi.h>

#include <mpm/parameters.h>
#include <mpm/verification.h>

#include <cmath>
#include <sstream>

namespace mpm
{
  void
  VerificationParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Verification");
    prm.declare_entry("exact solution",
                      "none",
                      Patterns::Selection(
                        "none|vibrating bar|self-weight column|displacement"),
                      "Known answer to compare with. 'vibrating bar': body 0 "
                      "is a bar fixed at its lower x end, started in mode 1 "
                      "with velocity amplitude 'amplitude'; the error is "
                      "|v_com - v0 cos(wt)/(beta L)| / v0, maximum over "
                      "output times. 'self-weight column': body 0 at rest "
                      "under gravity on a slip floor, with 'top pressure' p0 "
                      "on its top; the error is the volume-weighted RMS of "
                      "sigma_yy + p0 + rho g (H - y0) over p0 + rho g H, at "
                      "the end. 'displacement': the exact "
                      "displacement is 'exact displacement'; the errors are "
                      "sqrt(sum_p V_p |u_p - u(X_p, t)|^2) and max_p "
                      "|u_p - u(X_p, t)|, and for the velocity "
                      "sqrt(sum_p V_p |v_p - du/dt(X_p, t)|^2), each the "
                      "maximum over output times.");
    prm.declare_entry("exact displacement",
                      "0",
                      Patterns::Anything(),
                      "For 'displacement': u(X, t), one expression per "
                      "component separated by ';', in the initial position "
                      "x, y, z, time t and 'Simulation/constants'.");
    prm.declare_entry("amplitude",
                      "0.1",
                      Patterns::Anything(),
                      "Vibrating bar: velocity amplitude v0, > 0.");
    prm.declare_entry("top pressure",
                      "0",
                      Patterns::Anything(),
                      "Self-weight column: the pressure p0 >= 0 in Pa on "
                      "the top of the column (load it with 'loaded surface "
                      "= y max' and 'pressure' or 'traction' in the body).");
    prm.declare_entry("error bound",
                      "0",
                      Patterns::Anything(),
                      "Fail the run if the error exceeds this (0: no check).");
    prm.declare_entry("energy change bound",
                      "0",
                      Patterns::Anything(),
                      "Fail the run if the column energy_change, "
                      "|E(t) - E(0)| / |E(0)| with E the bodies' total "
                      "energy, ever exceeds this (0: no check). For scenes "
                      "that conserve energy: with loads, walls or "
                      "dissipation the change is physics (the numerics' "
                      "share is Simulation/energy residual's column).");
    prm.declare_entry("momentum change bound",
                      "0",
                      Patterns::Anything(),
                      "Fail the run if the column momentum_change, "
                      "|p(t) - p(0)| / sum_p m_p |v_p(0)|, ever exceeds "
                      "this (0: no check). For scenes without gravity, "
                      "walls or loads.");
    // The names before the columns were renamed (issue 33: 'drift' read as
    // an error where the change was plastic dissipation).
    prm.declare_alias("energy change bound", "energy drift bound", true);
    prm.declare_alias("momentum change bound", "momentum drift bound", true);
    prm.leave_subsection();
  }


  void
  VerificationParameters::parse_parameters(ParameterHandler &prm)
  {
    const std::string s = "Verification";
    constants           = Parse::constants(prm);
    prm.enter_subsection(s);
    const std::string e = prm.get("exact solution");
    exact               = e == "none"                 ? Exact::none
                          : e == "vibrating bar"      ? Exact::vibrating_bar
                          : e == "self-weight column" ? Exact::self_weight_column
                                                      : Exact::displacement;
    // The dimension is not known here: the list is checked in Verification.
    exact_displacement =
      Utilities::split_string_list(prm.get("exact displacement"), ';');
    amplitude    = Parse::bounded_double(prm, s, "amplitude", 0, 1e300, true);
    top_pressure = Parse::bounded_double(prm, s, "top pressure", 0, 1e300);
    error_bound  = Parse::bounded_double(prm, s, "error bound", 0, 1e300);
    energy_change_bound =
      Parse::bounded_double(prm, s, "energy change bound", 0, 1e300);
    momentum_change_bound =
      Parse::bounded_double(prm, s, "momentum change bound", 0, 1e300);
    prm.leave_subsection();
  }



  template <int dim>
  Verification<dim>::Verification(const VerificationParameters &parameters,
                                  const MaterialPoints<dim>    &points,
                                  const Tensor<1, dim>         &gravity,
                                  MPI_Comm                      comm)
    : prm(parameters)
    , points(points)
    , gravity(gravity)
    , comm(comm)
  {
    const auto &body = points.bodies()[0];
    if (prm.exact == VerificationParameters::Exact::displacement)
      {
        if (prm.exact_displacement.size() != dim)
          throw InputError(
            "Verification/exact displacement",
            prm.exact_displacement.empty() ? "" : prm.exact_displacement[0],
            "expects " + std::to_string(dim) + " expressions separated by ';'");
        exact_displacement =
          Parse::vector_function<dim>(prm.exact_displacement,
                                      prm.constants,
                                      "Verification/exact displacement");
      }
    else if (prm.exact != VerificationParameters::Exact::none &&
             body.shape_name != "box")
      throw InputError("Verification/exact solution",
                       "",
                       "needs body 0 to be a box");
    if (prm.exact == VerificationParameters::Exact::self_weight_column &&
        gravity.norm() == 0)
      throw InputError("Verification/exact solution",
                       "self-weight column",
                       "needs a non-zero 'Simulation/gravity'");
  }


  template <int dim>
  bool
  Verification<dim>::needs_initial_position(const VerificationParameters &p)
  {
    return p.exact == VerificationParameters::Exact::self_weight_column ||
           p.exact == VerificationParameters::Exact::displacement;
  }


  template <int dim>
  std::vector<std::string>
  Verification<dim>::columns() const
  {
    std::vector<std::string> c;
    if (prm.exact != VerificationParameters::Exact::none)
      c.push_back("error");
    if (prm.exact == VerificationParameters::Exact::displacement)
      {
        c.push_back("error_max");
        c.push_back("velocity_error");
      }
    c.push_back("energy_change");
    c.push_back("momentum_change");
    return c;
  }


  template <int dim>
  double
  Verification<dim>::exact_solution_error(const double t) const
  {
    const auto        &body = points.bodies()[0];
    const FieldLayout &l    = points.layout();
    if (prm.exact == VerificationParameters::Exact::vibrating_bar)
      {
        // Mode 1 of a bar fixed at x = 0 and free at x = L:
        // v(x, t) = v0 sin(beta x) cos(omega t), beta = pi / (2L).
        const double L = body.upper_corner[0] - body.lower_corner[0];
        const double c =
          std::sqrt(body.material->p_wave_modulus() / body.density);
        const double beta = numbers::PI / (2 * L);
        const double exact =
          prm.amplitude * std::cos(beta * c * t) / (beta * L);
        double mv = 0, m = 0;
        for (const auto &p : points.handler())
          {
            const double *q = p.get_properties().data();
            if (q[l.body] != 0)
              continue;
            mv += q[l.mass] * q[l.velocity];
            m += q[l.mass];
          }
        mv = Utilities::MPI::sum(mv, comm);
        m  = Utilities::MPI::sum(m, comm);
        return std::abs(mv / m - exact) / prm.amplitude;
      }

    // Self-weight column: uniaxial stress sigma_yy = -p0 - rho g (H - y0).
    const unsigned int up     = dim - 1;
    const double       g      = gravity.norm();
    const double       top    = body.upper_corner[up];
    const double       height = top - body.lower_corner[up];
    double             sum = 0, volume = 0;
    for (const auto &p : points.handler())
      {
        const double *q = p.get_properties().data();
        if (q[l.body] != 0)
          continue;
        const double y0    = q[l.initial_position + up];
        const double exact = -prm.top_pressure - body.density * g * (top - y0);
        const double e = Fields::symmetric<dim>(q + l.stress)[up][up] - exact;
        sum += q[l.volume] * e * e;
        volume += q[l.volume];
      }
    sum    = Utilities::MPI::sum(sum, comm);
    volume = Utilities::MPI::sum(volume, comm);
    return std::sqrt(sum / volume) /
           (prm.top_pressure + body.density * g * height);
  }


  template <int dim>
  std::array<double, 3>
  Verification<dim>::displacement_error(const double t) const
  {
    const FieldLayout &l = points.layout();
    // The exact velocity is du/dt by a central difference in time: the
    // scene states the displacement once. With a step of 1e-6 s the
    // relative error is about (omega dt)^2 / 6, 2e-8 for the fastest scene
    // here (omega = 100 pi), far below any discretisation error measured.
    const double dt  = 1e-6;
    auto         u_x = [&](const Point<dim> &X, const double time) {
      exact_displacement->set_time(time);
      Tensor<1, dim> u;
      for (unsigned int d = 0; d < dim; ++d)
        u[d] = exact_displacement->value(X, d);
      return u;
    };
    double sum = 0, max_norm = 0, velocity_sum = 0;
    for (const auto &p : points.handler())
      {
        const double        *q = p.get_properties().data();
        const Point<dim>     X(Fields::vector<dim>(q + l.initial_position));
        const Tensor<1, dim> e = p.get_location() - X - u_x(X, t);
        const Tensor<1, dim> v_exact =
          (u_x(X, t + dt) - u_x(X, t - dt)) / (2 * dt);
        sum += q[l.volume] * e.norm_square();
        max_norm = std::max(max_norm, e.norm());
        velocity_sum +=
          q[l.volume] *
          (Fields::vector<dim>(q + l.velocity) - v_exact).norm_square();
      }
    return {{std::sqrt(Utilities::MPI::sum(sum, comm)),
             Utilities::MPI::max(max_norm, comm),
             std::sqrt(Utilities::MPI::sum(velocity_sum, comm))}};
  }


  template <int dim>
  std::vector<double>
  Verification<dim>::evaluate(const Statistics<dim> &s, const double t)
  {
    if (!have_initial_state)
      {
        initial_energy         = s.total_energy();
        initial_momentum       = s.momentum;
        initial_momentum_scale = s.momentum_scale;
        have_initial_state     = true;
      }
    std::vector<double> values;
    if (prm.exact == VerificationParameters::Exact::displacement)
      {
        const auto [l2, linf, velocity_l2] = displacement_error(t);
        last_error                         = l2;
        max_error                          = std::max(max_error, l2);
        max_error_max_norm                 = std::max(max_error_max_norm, linf);
        max_velocity_error = std::max(max_velocity_error, velocity_l2);
        values.push_back(l2);
        values.push_back(linf);
        values.push_back(velocity_l2);
      }
    else if (prm.exact != VerificationParameters::Exact::none)
      {
        last_error = exact_solution_error(t);
        max_error  = std::max(max_error, last_error);
        values.push_back(last_error);
      }
    const double energy_change =
      initial_energy != 0
        ? std::abs(s.total_energy() - initial_energy) / std::abs(initial_energy)
        : 0;
    const double momentum_change =
      initial_momentum_scale > 0
        ? (s.momentum - initial_momentum).norm() / initial_momentum_scale
        : 0;
    max_energy_change   = std::max(max_energy_change, energy_change);
    max_momentum_change = std::max(max_momentum_change, momentum_change);
    values.push_back(energy_change);
    values.push_back(momentum_change);
    return values;
  }


  template <int dim>
  void
  Verification<dim>::check(ConditionalOStream &out) const
  {
    // A scene that asks for no verification gets no verdict (the drifts are
    // still columns of statistics.csv): with gravity or walls, the momentum
    // "drift" is physics, not an error.
    if (prm.exact == VerificationParameters::Exact::none &&
        prm.energy_change_bound == 0 && prm.momentum_change_bound == 0)
      return;
    std::ostringstream failures;
    const bool         at_end =
      prm.exact == VerificationParameters::Exact::self_weight_column;
    const double error = at_end ? last_error : max_error;
    if (prm.exact != VerificationParameters::Exact::none)
      {
        if (prm.exact == VerificationParameters::Exact::displacement)
          out << "Verification: max-norm displacement error (max over time) = "
              << max_error_max_norm << "\n"
              << "Verification: velocity error (max over time) = "
              << max_velocity_error << "\n";
        out << "Verification: error "
            << (at_end ? "at the end" : "(max over time)") << " = " << error
            << (prm.error_bound > 0
                  ? " (bound " + std::to_string(prm.error_bound) + ")"
                  : "")
            << "\n";
        if (prm.error_bound > 0 && !(error <= prm.error_bound))
          failures << " error " << error << " > bound " << prm.error_bound
                   << ";";
      }
    out << "Verification: max energy change = " << max_energy_change
        << ", max momentum change = " << max_momentum_change << "\n";
    if (prm.energy_change_bound > 0 &&
        !(max_energy_change <= prm.energy_change_bound))
      failures << " energy change " << max_energy_change << " > bound "
               << prm.energy_change_bound << ";";
    if (prm.momentum_change_bound > 0 &&
        !(max_momentum_change <= prm.momentum_change_bound))
      failures << " momentum change " << max_momentum_change << " > bound "
               << prm.momentum_change_bound << ";";
    if (!failures.str().empty())
      throw RunError("verification failed:" + failures.str());
  }


  template <int dim>
  void
  Verification<dim>::save_state(RunState &state) const
  {
    auto &v                                  = state.values;
    v["verification_max_error"]              = max_error_max_norm;
    v["verification_max_velocity_error"]     = max_velocity_error;
    v["verification_have_initial_state"]     = have_initial_state;
    v["verification_initial_energy"]         = initial_energy;
    v["verification_initial_momentum_scale"] = initial_momentum_scale;
    for (unsigned int d = 0; d < dim; ++d)
      v["verification_initial_momentum_" + std::to_string(d)] =
        initial_momentum[d];
  }


  template <int dim>
  void
  Verification<dim>::restore_state(const RunState &state)
  {
    max_error_max_norm     = state.get("verification_max_error");
    max_velocity_error     = state.get("verification_max_velocity_error");
    have_initial_state     = state.get("verification_have_initial_state");
    initial_energy         = state.get("verification_initial_energy");
    initial_momentum_scale = state.get("verification_initial_momentum_scale");
    for (unsigned int d = 0; d < dim; ++d)
      initial_momentum[d] =
        state.get("verification_initial_momentum_" + std::to_string(d));
  }


  template class Verification<1>;
  template class Verification<2>;
  template class Verification<3>;
} // namespace mpm
