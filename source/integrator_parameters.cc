#include <mpm/integrator_parameters.h>
#include <mpm/parameters.h>

#include <cstdlib>

namespace mpm
{
  template <int dim>
  void
  IntegratorParameters<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Simulation");
    prm.declare_entry("constants",
                      "",
                      Patterns::Anything(),
                      "Named constants for every expression of the scene "
                      "(initial velocity, body force, exact solution), as "
                      "'name=value, ...'; pi is always known.");
    prm.declare_entry("end time",
                      "1",
                      Patterns::Anything(),
                      "Simulated time to reach, in s, > 0.");
    prm.declare_entry("CFL number",
                      "0.5",
                      Patterns::Anything(),
                      "Time step = CFL number * h / max_p(c_p + |v_p|), "
                      "re-evaluated every step; in (0, 0.8]: the range "
                      "stable with every basis (0.9 is not with the linear "
                      "basis and GIMP; benchmarks/verification/"
                      "cfl_range.py).");
    prm.declare_entry("time step",
                      "0",
                      Patterns::Anything(),
                      "A fixed time step in s, or 0 to use the CFL "
                      "condition. A fixed step larger than the CFL-limited "
                      "one is an error.");
    prm.declare_entry(
      "macro time step",
      "0",
      Patterns::Anything(),
      "Substepping (seed 003) in s, >= 0: the run advances in macro steps "
      "of this length, each made of explicit substeps; after them the grid "
      "velocity on the start-of-step configuration is reconstructed from "
      "the points' secant motion (the closed-form APIC transfer), and the "
      "macro-step operations ('kinetic damping') act on it. The points "
      "keep the substeps' state. Output and end times cut a macro step "
      "short. 0: off (plain explicit steps).");
    prm.declare_entry(
      "substeps",
      "0",
      Patterns::Integer(0, 1000000),
      "Substeps per macro step, in [0, 1000000]: 0 takes as many equal ones "
      "as the CFL condition needs (re-evaluated at every substep); S > 0 "
      "takes S equal ones, and one beyond the CFL limit stops the run.");
    prm.declare_entry(
      "kinetic damping",
      "false",
      Patterns::Bool(),
      "Macro-step operation for quasi-static runs (dynamic relaxation): when "
      "the kinetic energy of the reconstructed grid velocity has fallen "
      "since the last macro step (a peak has passed), every nodal velocity "
      "is set to zero and the points take it (velocity and APIC's C_p). "
      "Needs a macro time step.");
    prm.declare_entry(
      "macro reconstruction",
      "APIC",
      Patterns::Selection("APIC|least squares"),
      "How the macro step's grid velocity is fitted to the points' secant "
      "motion (seed 003): APIC, the closed form (lumped mass, one transfer), "
      "or least squares, its system (4) with the consistent mass and "
      "'least-squares weight' times the gradient term, solved by conjugate "
      "gradients (Trilinos); single-field scenes only.");
    prm.declare_entry(
      "least-squares weight",
      "0.25",
      Patterns::Anything(),
      "lambda / h^2 of the least-squares reconstruction, in [0, 100]: how "
      "much the points' velocity gradients count beside their velocities; "
      "0.25 is seed 003's natural scaling D = h^2/4 of the quadratic "
      "B-spline.");
    prm.declare_entry("least-squares preconditioner",
                      "Jacobi",
                      Patterns::Selection("Jacobi|AMG"),
                      "Preconditioner of the least-squares conjugate "
                      "gradients: Jacobi, or AMG (Trilinos ML).");
    prm.declare_entry(
      "Newmark gamma",
      "0.5",
      Patterns::Anything(),
      "gamma of the explicit Newmark step (beta = 0, the only explicit "
      "member), in [0.5, 1]: 0.5 is central difference, which the plain "
      "step is (second order, no numerical damping); above it the "
      "high frequencies are damped (amplitude loss per step about "
      "(gamma - 1/2) (omega dt)^2 / 2) at first order in dt, and the CFL "
      "time step is scaled by 1 / sqrt(2 gamma) to stay stable. USL with "
      "FLIP only (doc/architecture.md).");
    prm.declare_entry("update scheme",
                      "USL",
                      Patterns::Selection(update_scheme_names.selection()),
                      "When stresses are updated: USL (last, from the new "
                      "grid velocity), USF (first) or MUSL (last, from "
                      "particle velocities mapped back to the grid).");
    prm.declare_entry("basis",
                      "linear",
                      Patterns::Selection(basis_names.selection()),
                      "Shape functions between points and grid nodes: "
                      "linear, uGIMP (each point a domain of h / points per "
                      "cell), cpGIMP (that domain stretched with F), "
                      "quadratic B-spline or cubic B-spline. The smoother "
                      "ones reduce the error of points crossing cell faces; "
                      "B-splines are folded at the grid boundary so that "
                      "walls hold.");
    prm.declare_entry("transfer",
                      "FLIP",
                      Patterns::Selection(transfer_names.selection()),
                      "Velocity transfer: FLIP (the PIC/FLIP blend set by "
                      "'FLIP fraction') or APIC (points carry an affine "
                      "velocity; conserves angular momentum; 'FLIP "
                      "fraction' is then not used).");
    prm.declare_entry("FLIP fraction",
                      "0.99",
                      Patterns::Anything(),
                      "PIC/FLIP blend alpha in [0, 1]: 0 is PIC (dissipative, "
                      "stable), 1 is FLIP (conserves energy, noisier). It "
                      "acts once per step, so its damping grows as the step "
                      "shrinks; see 'PIC relaxation time'.");
    prm.declare_entry(
      "PIC relaxation time",
      "0",
      Patterns::Anything(),
      "FLIP only: the time in s over which a point's velocity relaxes to "
      "the grid's (PIC), in place of 'FLIP fraction': each step blends with "
      "alpha = exp(-dt / time). The damping then does not depend on the "
      "time step, and in a shear band a cell wide it shrinks with the "
      "grid; a longer time damps less (benchmarks/granular/README.md). "
      "0: off (the FLIP fraction).");
    prm.declare_entry("gravity",
                      "0",
                      Patterns::Anything(),
                      "Gravitational acceleration in m/s^2, one value per "
                      "dimension (e.g. '0, -9.81').");
    prm.declare_entry("damping",
                      "0",
                      Patterns::Anything(),
                      "Global mass-proportional velocity damping c in 1/s, "
                      ">= 0: grid velocities obey dv/dt = f/m - c v (as in "
                      "cl-mpm), for quasi-static problems.");
    prm.declare_entry("local damping",
                      "0",
                      Patterns::Anything(),
                      "Local (Cundall) non-viscous damping alpha in [0, 1): "
                      "each component of a node's unbalanced force f is "
                      "reduced by alpha |f| against the node's velocity, so "
                      "that a body at rest feels none and a moving one "
                      "loses a fixed fraction of its work: quasi-static "
                      "runs settle in fewer steps. 0: off; 0.8 is usual.");
    prm.declare_entry("mass scaling",
                      "1",
                      Patterns::Anything(),
                      "Inertia factor s >= 1 for quasi-static runs: the "
                      "nodal masses in the momentum balance are s times the "
                      "true ones (loads and gravity are not), so waves are "
                      "sqrt(s) slower and the CFL time step sqrt(s) larger. "
                      "1: off. Dynamics are wrong by design; use it only "
                      "where the answer is static or slow.");
    prm.declare_entry(
      "J bounds",
      "1e-3, 1e3",
      Patterns::Anything(),
      "Run-health guard: the run stops, naming the point, when a point's "
      "volume ratio J = V / V0 leaves [J_min, J_max] (a point crushed to "
      "nothing or torn apart is a run gone wrong, not physics); two "
      "numbers, 0 < J_min < 1 < J_max. Granular flows that spread far may "
      "need a larger J_max.");
    prm.declare_entry(
      "F-bar",
      "false",
      Patterns::Bool(),
      "Volumetric locking remedy for nearly incompressible materials "
      "(Poisson's ratio near 0.5, fluids; plastic flow that keeps the "
      "volume, as Mohr-Coulomb with psi = 0): each step, every point's "
      "volume change is replaced by the volume change of its body's points "
      "in its cell (F-bar), so that a cell carries one volumetric constraint "
      "instead of one per point, and the internal force takes each point's "
      "stress with its cell's mean stress (the pair keeps the energy). The "
      "deviatoric part of each point's deformation is kept. Materials whose "
      "volume has a history (Mohr-Coulomb, Drucker-Prager) share each "
      "step's volume change; the others share J itself.");
    prm.declare_entry(
      "energy growth bound",
      "0.25",
      Patterns::Anything(),
      "Run-health guard: the run stops, naming the fastest point, when the "
      "energy of the bodies (kinetic, strain, gravitational) has grown "
      "beyond the work done on them by more than this fraction of the "
      "energy put in (initial motion and strain, gravitational energy "
      "released, work of loads, walls, regions and the virtual fluid); "
      "checked at output times; >= 0, 0: off.");
    prm.declare_entry(
      "energy residual",
      "false",
      Patterns::Bool(),
      "Add the energy balance's columns to statistics.csv: "
      "external_work W (J: loads, body forces, rigid walls and bodies, "
      "velocity regions, the virtual fluid), dissipation D (J: the work "
      "the stresses absorbed, the stress power summed over the steps, less "
      "the strain energy they store: plastic, viscous and damage "
      "dissipation), the work of the grid (J, negative where it takes "
      "energy out; at each force update: "
      "face_friction_work, Coulomb friction on friction faces; face_work, "
      "the other face rules: velocity into fixed, slip and friction faces "
      "taken out, fixed faces' tangential hold, absorbing dashpots; "
      "damping_work, global and local damping; contact_work, in scenes "
      "with contact, the inelastic closing and friction against rigid "
      "bodies) and energy_residual R over "
      "the energy put in, so that the total energy changes by E - E(0) = "
      "W - D + face_friction_work + face_work + damping_work + "
      "contact_work + R (with APIC E counts the points' affine velocity "
      "fields, column affine_kinetic_energy). R is the "
      "numerics' share, which plasticity cannot hide as it hides it in the "
      "total energy (> 0: made; < 0: lost to the transfer, to contact "
      "between deformable bodies and to the time stepping). The energy "
      "growth bound "
      "then applies to R "
      "too. Costs two passes over the points per step.");
    prm.declare_entry("small mass fraction",
                      "0.25",
                      Patterns::Anything(),
                      "USL with the linear basis: nodes whose mass is below "
                      "this fraction of the smallest point mass are left "
                      "out of the velocity gradient and, the same way, out "
                      "of the internal force (so that its work stays the "
                      "stress power and momentum is conserved); APIC's "
                      "affine velocity and contact treat them as the edge "
                      "of a body. MUSL and USF, and the smooth bases, need "
                      "no guard in the velocity gradient. In [0, 1).");
    prm.declare_entry("out of grid",
                      "stop",
                      Patterns::Selection("stop|remove"),
                      "What happens to a material point that leaves the "
                      "grid: stop the run with a message naming it, or "
                      "remove it and count it in the statistics.");
    prm.leave_subsection();
  }


  template <int dim>
  void
  IntegratorParameters<dim>::parse_parameters(ParameterHandler &prm)
  {
    const std::string s = "Simulation";
    prm.enter_subsection(s);
    end_time = Parse::bounded_double(prm, s, "end time", 0, 1e300, true);
    // The limit is lifted only to measure it (cfl_range.py).
    const char  *lifted  = std::getenv("DEALII_MPM_MAX_CFL");
    const double max_cfl = lifted != nullptr ? std::atof(lifted) : 0.8;
    cfl_number = Parse::bounded_double(prm, s, "CFL number", 0, max_cfl, true);
    fixed_time_step = Parse::bounded_double(prm, s, "time step", 0, 1e300);
    scheme          = update_scheme_names.value(prm.get("update scheme"));
    basis           = basis_names.value(prm.get("basis"));
    transfer        = transfer_names.value(prm.get("transfer"));
    flip_fraction   = Parse::bounded_double(prm, s, "FLIP fraction", 0, 1);
    pic_relaxation_time =
      Parse::bounded_double(prm, s, "PIC relaxation time", 0, 1e300);
    gravity = Parse::vector<dim>(prm, s, "gravity");
    damping = Parse::bounded_double(prm, s, "damping", 0, 1e300);
    local_damping =
      Parse::bounded_double(prm, s, "local damping", 0, 1, false, true);
    mass_scaling = Parse::bounded_double(prm, s, "mass scaling", 1, 1e12);
    small_mass_fraction =
      Parse::bounded_double(prm, s, "small mass fraction", 0, 1, false, true);
    const auto J_bounds = Parse::double_list(prm, s, "J bounds", 2);
    J_min               = J_bounds[0];
    J_max               = J_bounds[1];
    if (!(J_min > 0 && J_min < 1 && J_max > 1))
      throw InputError("Simulation/J bounds",
                       prm.get("J bounds"),
                       "must be two numbers J_min, J_max with 0 < J_min < 1 "
                       "< J_max");
    f_bar = prm.get_bool("F-bar");
    energy_growth_bound =
      Parse::bounded_double(prm, s, "energy growth bound", 0, 1e300);
    energy_residual = prm.get_bool("energy residual");
    out_of_grid     = prm.get("out of grid") == "stop" ? OutOfGridPolicy::stop
                                                       : OutOfGridPolicy::remove;
    macro_time_step =
      Parse::bounded_double(prm, s, "macro time step", 0, 1e300);
    substeps        = prm.get_integer("substeps");
    kinetic_damping = prm.get_bool("kinetic damping");
    least_squares   = prm.get("macro reconstruction") == "least squares";
    least_squares_weight =
      Parse::bounded_double(prm, s, "least-squares weight", 0, 100);
    least_squares_amg = prm.get("least-squares preconditioner") == "AMG";
    newmark_gamma     = Parse::bounded_double(prm, s, "Newmark gamma", 0.5, 1);
    const bool blends_pic =
      with_transfer(transfer, [](auto c) { return c.blends_pic; });
    if (newmark_gamma != 0.5 && (scheme != UpdateScheme::USL || !blends_pic))
      throw InputError("Simulation/Newmark gamma",
                       prm.get("Newmark gamma"),
                       "other than 0.5 needs 'Simulation/update scheme = "
                       "USL' and 'Simulation/transfer = FLIP'");
    if (pic_relaxation_time > 0 && !blends_pic)
      throw InputError("Simulation/PIC relaxation time",
                       prm.get("PIC relaxation time"),
                       "must be 0 unless 'Simulation/transfer = FLIP'");
    if (macro_time_step > 0 && fixed_time_step > 0)
      throw InputError("Simulation/time step",
                       prm.get("time step"),
                       "must be 0 with 'Simulation/macro time step' > 0 "
                       "(the substeps are set by 'Simulation/substeps')");
    if (macro_time_step == 0 && substeps > 0)
      throw InputError("Simulation/substeps",
                       prm.get("substeps"),
                       "must be 0 without 'Simulation/macro time step'");
    if (macro_time_step == 0 && kinetic_damping)
      throw InputError("Simulation/kinetic damping",
                       "true",
                       "needs 'Simulation/macro time step' > 0 (it acts "
                       "once per macro step)");
    prm.leave_subsection();
  }


  template struct IntegratorParameters<1>;
  template struct IntegratorParameters<2>;
  template struct IntegratorParameters<3>;
} // namespace mpm
