#include <deal.II/base/function_parser.h>
#include <deal.II/base/mpi.h>

#include <mpm/material_points.h>
#include <mpm/parameters.h>

#include <sstream>

namespace mpm
{


  template <int dim>
  void
  BodyParameters<dim>::declare_parameters(ParameterHandler  &prm,
                                          const unsigned int index)
  {
    prm.enter_subsection("Bodies");
    prm.enter_subsection("Body " + std::to_string(index));
    prm.declare_entry("shape",
                      "box",
                      Patterns::Selection("box|ball"),
                      "Shape of the body: box (lower/upper corner) or ball "
                      "(center/radius; a disk in 2D).");
    prm.declare_entry(
      "lower corner",
      "0.25",
      Patterns::Anything(),
      "Box: lower corner, one value per dimension or one for all.");
    prm.declare_entry("upper corner",
                      "0.75",
                      Patterns::Anything(),
                      "Box: upper corner.");
    prm.declare_entry("center", "0.5", Patterns::Anything(), "Ball: center.");
    prm.declare_entry("radius",
                      "0.25",
                      Patterns::Anything(),
                      "Ball: radius, > 0.");
    prm.declare_entry("inner radius",
                      "0",
                      Patterns::Anything(),
                      "Ball: radius of a hole at the centre, in [0, radius): "
                      "a ring in 2D, a spherical shell in 3D.");
    prm.declare_entry("particles per cell",
                      "2",
                      Patterns::Anything(),
                      "Material points per cell and direction, in [1, 10].");
    prm.declare_entry("density",
                      "1000",
                      Patterns::Anything(),
                      "Initial mass density in kg/m^3, > 0.");
    prm.declare_entry("initial velocity",
                      "0",
                      Patterns::Anything(),
                      "Initial velocity: one expression per component "
                      "separated by ';' (or one for all), in the variables "
                      "x, y, z of the initial position; pi is known. "
                      "Example: '0.1*sin(pi*x/50)'.");
    prm.declare_entry("initial displacement",
                      "0",
                      Patterns::Anything(),
                      "Displacement u0(X) of the body at t = 0 from its shape "
                      "(the reference configuration): one expression per "
                      "component in x, y, z (or one for all). Points start at "
                      "X + u0 with F = I + grad u0 and the stress of that F; "
                      "needs a material whose stress follows from F "
                      "(neo-Hookean).");
    prm.declare_entry(
      "initial stress",
      "0",
      Patterns::Anything(),
      "Cauchy stress at t = 0 in Pa, tension positive: expressions in x, y, "
      "z separated by ';' for the components xx; yy; zz (1D), xx; yy; zz; xy "
      "(2D, plane strain: zz is the out-of-plane stress) or xx; yy; zz; xy; "
      "yz; xz (3D); e.g. a geostatic state 'K0*rho*g*(y-H); rho*g*(y-H); "
      "K0*rho*g*(y-H); 0' with constants. The material starts with the "
      "state that carries it (elastic strain); a plastic material must "
      "hold it inside its yield surface.");
    prm.declare_entry("body force",
                      "0",
                      Patterns::Anything(),
                      "Body force per unit mass (besides gravity), in m/s^2: "
                      "one expression per component separated by ';' (or "
                      "one for all), in the initial position x, y, z of the "
                      "point and time t, e.g. for manufactured solutions. "
                      "Non-zero makes every point store its initial position.");
    prm.declare_entry("material",
                      "linear elastic",
                      Patterns::Selection(MaterialRegistry::names()),
                      "Constitutive model, one of: " +
                        MaterialRegistry::names() +
                        ". Its parameters are read from the subsection of the "
                        "same name.");
    MaterialRegistry::declare_parameters(prm);
    prm.leave_subsection();
    prm.leave_subsection();
  }


  template <int dim>
  void
  BodyParameters<dim>::parse_parameters(ParameterHandler  &prm,
                                        const unsigned int index)
  {
    name      = "Bodies/Body " + std::to_string(index);
    constants = Parse::constants(prm);
    prm.enter_subsection("Bodies");
    prm.enter_subsection("Body " + std::to_string(index));
    shape = prm.get("shape") == "box" ? Shape::box : Shape::ball;
    if (shape == Shape::box)
      {
        lower_corner = Parse::point<dim>(prm, name, "lower corner");
        upper_corner = Parse::point<dim>(prm, name, "upper corner");
        for (unsigned int d = 0; d < dim; ++d)
          if (!(upper_corner[d] > lower_corner[d]))
            throw InputError(name + "/upper corner",
                             prm.get("upper corner"),
                             "must exceed the lower corner in every direction");
      }
    else
      {
        center = Parse::point<dim>(prm, name, "center");
        radius = Parse::bounded_double(prm, name, "radius", 0, 1e300, true);
        inner_radius = Parse::bounded_double(
          prm, name, "inner radius", 0, radius, false, true);
        for (unsigned int d = 0; d < dim; ++d)
          {
            lower_corner[d] = center[d] - radius;
            upper_corner[d] = center[d] + radius;
          }
      }
    particles_per_cell = static_cast<unsigned int>(
      Parse::bounded_double(prm, name, "particles per cell", 1, 10));
    if (particles_per_cell != prm.get_double("particles per cell"))
      throw InputError(name + "/particles per cell",
                       prm.get("particles per cell"),
                       "must be a whole number in [1, 10]");
    density = Parse::bounded_double(prm, name, "density", 0, 1e300, true);
    initial_velocity =
      Parse::expression_list(prm, "initial velocity", dim, name);
    initial_displacement =
      Parse::expression_list(prm, "initial displacement", dim, name);
    initial_stress   = Parse::expression_list(prm,
                                            "initial stress",
                                            dim == 1   ? 3
                                              : dim == 2 ? 4
                                                         : 6,
                                            name);
    const auto force = Parse::expression_list(prm, "body force", dim, name);
    if (!Parse::is_zero(force))
      body_force =
        Parse::vector_function<dim>(force, constants, name + "/body force");
    material_name = prm.get("material");
    material = MaterialRegistry::create<dim>(material_name, prm, name, density);
    if (is_displaced() && !material->needs_deformation_gradient())
      throw InputError(name + "/initial displacement",
                       prm.get("initial displacement"),
                       "needs a material whose stress follows from F "
                       "(neo-Hookean); '" +
                         material_name + "' has no reference state");
    if (is_prestressed() && !material->accepts_initial_stress())
      throw InputError(name + "/initial stress",
                       prm.get("initial stress"),
                       "'" + material_name +
                         "' takes its stress from F alone and cannot start "
                         "stressed; use a model with an elastic state "
                         "(linear elastic, Hencky elastic, the plastic "
                         "models)");
    prm.leave_subsection();
    prm.leave_subsection();
  }


  template <int dim>
  template <typename Visitor>
  void
  BodyParameters<dim>::for_each_seed(const Point<dim>     &cell_origin,
                                     const Tensor<1, dim> &h,
                                     const Visitor        &visit) const
  {
    const unsigned int n = particles_per_cell;
    for (unsigned int s = 0; s < Utilities::fixed_power<dim>(n); ++s)
      {
        // Points at the centres of n^dim sub-cells: interior, never on a
        // face, where deal.II 9.4's in-cell test can lose them.
        Point<dim>   xi;
        unsigned int rest = s;
        for (unsigned int d = 0; d < dim; ++d)
          {
            xi[d] = ((rest % n) + 0.5) / n;
            rest /= n;
          }
        Point<dim> x = cell_origin;
        for (unsigned int d = 0; d < dim; ++d)
          x[d] += xi[d] * h[d];
        if (contains(x))
          visit(x, xi);
      }
  }


  template <int dim>
  unsigned int
  BodyParameters<dim>::count_seeds(const Point<dim>     &cell_origin,
                                   const Tensor<1, dim> &h) const
  {
    unsigned int n = 0;
    for_each_seed(cell_origin, h, [&n](const Point<dim> &, const Point<dim> &) {
      ++n;
    });
    return n;
  }


  template <int dim>
  bool
  BodyParameters<dim>::is_displaced() const
  {
    return !Parse::is_zero(initial_displacement);
  }


  template <int dim>
  bool
  BodyParameters<dim>::is_prestressed() const
  {
    return !Parse::is_zero(initial_stress);
  }


  template <int dim>
  bool
  BodyParameters<dim>::contains(const Point<dim> &x) const
  {
    if (shape == Shape::ball)
      {
        const double r2 = x.distance_square(center);
        return r2 < radius * radius && r2 >= inner_radius * inner_radius;
      }
    for (unsigned int d = 0; d < dim; ++d)
      if (x[d] < lower_corner[d] || x[d] > upper_corner[d])
        return false;
    return true;
  }



  template <int dim>
  MaterialPoints<dim>::MaterialPoints(
    const BackgroundGrid<dim>              &grid,
    const std::vector<BodyParameters<dim>> &bodies,
    const FieldRequests                    &requests,
    MPI_Comm                                comm)
    : grid(grid)
    , body_list(bodies)
    , comm(comm)
    , fields(assemble_layout(requests))
    , particles(grid.triangulation(), grid.mapping(), fields.n_properties)
    , minimum_mass(0)
  {
    for (const auto &b : body_list)
      if (!grid.contains(b.lower_corner, b.upper_corner))
        {
          std::ostringstream s;
          s << "(" << b.lower_corner << ") to (" << b.upper_corner << ")";
          throw InputError(b.name + (b.shape == BodyParameters<dim>::Shape::box
                                       ? "/upper corner"
                                       : "/radius"),
                           s.str(),
                           "the body must lie inside the grid box");
        }
  }


  template <int dim>
  FieldLayout
  MaterialPoints<dim>::assemble_layout(FieldRequests requests) const
  {
    for (const auto &b : body_list)
      b.material->request_fields(requests);
    return mpm::assemble_layout<dim>(requests);
  }


  template <int dim>
  void
  MaterialPoints<dim>::generate()
  {
    const FieldLayout      &l = fields;
    std::vector<Point<dim>> positions;
    std::vector<Point<dim>> displaced_positions;              // at t = 0
    std::vector<std::pair<unsigned int, unsigned int>> where; // (cell, body)
    std::vector<std::vector<double>>                   props;
    std::vector<Point<dim>>                            references;
    double                                             cell_volume = 1;
    for (unsigned int d = 0; d < dim; ++d)
      cell_volume *= grid.cell_size()[d];

    std::vector<types::particle_index> count(body_list.size(), 0);
    minimum_mass = std::numeric_limits<double>::max();
    for (unsigned int b = 0; b < body_list.size(); ++b)
      {
        const auto &body = body_list[b];
        // The difference step of the velocity gradient (APIC's initial
        // C_p = grad v0): a fourth-order formula with a step of 1e-3 cells
        // is exact for affine fields up to round-off of about 1e-13.
        const auto velocity =
          Parse::vector_function<dim>(body.initial_velocity,
                                      body.constants,
                                      body.name + "/initial velocity",
                                      1e-3 * grid.min_cell_size());
        velocity->set_formula(AutoDerivativeFunction<dim>::FourthOrder);
        std::unique_ptr<FunctionParser<dim>> displacement;
        if (body.is_displaced())
          {
            displacement =
              Parse::vector_function<dim>(body.initial_displacement,
                                          body.constants,
                                          body.name + "/initial displacement",
                                          1e-3 * grid.min_cell_size());
            displacement->set_formula(AutoDerivativeFunction<dim>::FourthOrder);
          }
        std::unique_ptr<FunctionParser<dim>> stress;
        if (body.is_prestressed())
          stress = Parse::vector_function<dim>(body.initial_stress,
                                               body.constants,
                                               body.name + "/initial stress");
        const unsigned int n      = body.particles_per_cell;
        const unsigned int n_sub  = Utilities::fixed_power<dim>(n);
        const double       volume = cell_volume / n_sub;
        const double       mass   = body.density * volume;
        minimum_mass              = std::min(minimum_mass, mass);
        for (const auto &cell : grid.triangulation().active_cell_iterators())
          if (cell->is_locally_owned())
            body.for_each_seed(
              cell->vertex(0),
              grid.cell_size(),
              [&](const Point<dim> &x, const Point<dim> &xi) {
                std::vector<double> p(l.n_properties, 0.);
                p[l.mass]   = mass;
                p[l.volume] = volume;
                p[l.body]   = b;
                for (unsigned int d = 0; d < dim; ++d)
                  p[l.velocity + d] = velocity->value(x, d);
                if (l.deformation_gradient != FieldLayout::absent)
                  for (unsigned int d = 0; d < dim; ++d)
                    p[l.deformation_gradient + d * dim + d] = 1.;
                if (l.affine_velocity != FieldLayout::absent)
                  for (unsigned int c = 0; c < dim; ++c)
                    {
                      const Tensor<1, dim> g = velocity->gradient(x, c);
                      for (unsigned int d = 0; d < dim; ++d)
                        p[l.affine_velocity + c * dim + d] = g[d];
                    }
                if (l.initial_position != FieldLayout::absent)
                  for (unsigned int d = 0; d < dim; ++d)
                    p[l.initial_position + d] = x[d];
                initialise_state(body, stress.get(), x, p.data());
                Point<dim> start = x;
                if (displacement)
                  start = displace(*displacement, x, p.data());
                positions.push_back(x);
                displaced_positions.push_back(start);
                references.push_back(xi);
                where.emplace_back(grid.cartesian_index(cell), b);
                props.push_back(std::move(p));
                ++count[b];
              });
      }
    minimum_mass = Utilities::MPI::min(minimum_mass, comm);
    raise_if_any_failed(state_failure, comm, true);

    for (unsigned int b = 0; b < body_list.size(); ++b)
      if (Utilities::MPI::sum(count[b], comm) == 0)
        throw InputError(body_list[b].name + "/particles per cell",
                         std::to_string(body_list[b].particles_per_cell),
                         "no material point falls inside the body: make it "
                         "larger than a cell or use more points per cell");

    // Globally unique ids, numbered rank by rank.
    const types::particle_index n_local = positions.size();
    types::particle_index       first   = 0;
    MPI_Exscan(&n_local,
               &first,
               1,
               Utilities::MPI::mpi_type_id_for_type<types::particle_index>,
               MPI_SUM,
               comm);
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      first = 0; // MPI_Exscan leaves rank 0's result undefined
    particles.reserve(n_local);
    for (types::particle_index i = 0; i < n_local; ++i)
      particles.insert_particle(positions[i],
                                references[i],
                                first + i,
                                grid.cell(where[i].first),
                                make_array_view(props[i]));
    particles.update_cached_numbers();

    // Displaced bodies: the points were put in the cells of their reference
    // positions; move them to where they start, then give them the stress
    // of their initial F.
    bool any_displaced = false;
    for (const auto &body : body_list)
      any_displaced = any_displaced || body.is_displaced();
    if (any_displaced)
      {
        for (auto &p : particles)
          p.set_location(displaced_positions[p.get_id() - first]);
        relocate(OutOfGridPolicy::stop);
        for (unsigned int b = 0; b < body_list.size(); ++b)
          if (body_list[b].is_displaced())
            body_list[b].material->update_stresses(particles, fields, b, 0.);
      }
  }


  template <int dim>
  void
  MaterialPoints<dim>::initialise_state(const BodyParameters<dim> &body,
                                        FunctionParser<dim>       *stress,
                                        const Point<dim>          &x,
                                        double                    *properties)
  {
    // Components in the order of 'initial stress'.
    static constexpr unsigned int rows[6] = {0, 1, 2, 0, 1, 0};
    static constexpr unsigned int cols[6] = {0, 1, 2, 1, 2, 2};
    SymmetricTensor<2, 3>         sigma0;
    if (stress != nullptr)
      for (unsigned int c = 0; c < stress->n_components; ++c)
        sigma0[rows[c]][cols[c]] = stress->value(x, c);
    try
      {
        body.material->initialise_point(properties, fields, sigma0);
      }
    catch (const std::domain_error &e)
      {
        std::ostringstream where;
        where << "the stress (" << sigma0 << ") at (" << x << ") " << e.what()
              << " of '" << body.material_name << "'";
        std::string text;
        for (const auto &e : body.initial_stress)
          text += (text.empty() ? "" : "; ") + e;
        // Raised collectively after generation (one rank alone must not
        // stop).
        if (state_failure.empty())
          state_failure =
            InputError(body.name + "/initial stress", text, where.str()).what();
      }
  }


  template <int dim>
  Point<dim>
  MaterialPoints<dim>::displace(const FunctionParser<dim> &displacement,
                                const Point<dim>          &X,
                                double                    *properties) const
  {
    const FieldLayout &l = fields;
    Point<dim>         x = X;
    Tensor<2, dim>     F;
    for (unsigned int c = 0; c < dim; ++c)
      {
        x[c] += displacement.value(X, c);
        F[c] = displacement.gradient(X, c);
        F[c][c] += 1.;
      }
    const double J = determinant(F);
    if (!(J > 0))
      {
        std::ostringstream where;
        where << "det(I + grad u0) = " << J << " <= 0 at X = (" << X
              << "): the initial displacement must not invert the body";
        throw InputError(body_list[properties[l.body]].name +
                           "/initial displacement",
                         "",
                         where.str());
      }
    Fields::store(F, properties + l.deformation_gradient);
    properties[l.volume] *= J;
    return x;
  }


  template <int dim>
  types::particle_index
  MaterialPoints<dim>::relocate(const OutOfGridPolicy policy)
  {
    using iterator =
      typename Particles::ParticleHandler<dim>::particle_iterator;
    // Points to delete from their old place, in visiting order: those that
    // moved to another cell of this rank (a copy was inserted there) and
    // those that left the grid.
    std::vector<iterator> removals;
    std::string           failure;
    types::particle_index n_lost   = 0;
    bool                  off_rank = false;
    std::vector<double>   buffer(fields.n_properties);

    for (const unsigned int here : grid.locally_owned_cells())
      {
        const auto &cell = grid.cell(here);
        // Count, not end(): inserting into a previously empty cell adds a
        // container entry that end() of this range could then point to.
        const unsigned int n = particles.n_particles_in_cell(cell);
        if (n == 0)
          continue;
        auto p = particles.particles_in_cell(cell).begin();
        for (unsigned int i = 0; i < n; ++i, ++p)
          {
            Point<dim>         xi;
            const unsigned int there = grid.locate(p->get_location(), xi);
            if (there == here)
              p->set_reference_location(xi);
            else if (there == BackgroundGrid<dim>::invalid)
              {
                // A NaN position is an unstable run, not a point that left:
                // it must never be removed quietly.
                const bool finite =
                  std::isfinite(p->get_location().norm_square());
                if (!finite || policy == OutOfGridPolicy::stop)
                  {
                    if (failure.empty())
                      failure = finite ? describe_leaving_point(p)
                                       : "material point " +
                                           std::to_string(p->get_id()) +
                                           " has a non-finite position; the "
                                           "run is unstable (try a smaller "
                                           "CFL number, MUSL, or damping)";
                    continue;
                  }
                removals.push_back(p);
                ++n_lost;
              }
            else if (grid.cell(there)->is_locally_owned())
              {
                // Copy first: the location and properties live in deal.II's
                // property pool, which inserting may reallocate.
                const auto       src = p->get_properties();
                const Point<dim> x   = p->get_location();
                std::copy(src.begin(), src.end(), buffer.begin());
                particles.insert_particle(x,
                                          xi,
                                          p->get_id(),
                                          grid.cell(there),
                                          make_array_view(buffer));
                removals.push_back(p);
              }
            else
              off_rank = true;
          }
      }

    raise_if_any_failed(failure, comm);

    // Removing in reverse visiting order removes the highest index of each
    // cell first, so the iterators still to be used stay valid.
    for (auto p = removals.rbegin(); p != removals.rend(); ++p)
      particles.remove_particle(*p);

    // Both calls below are collective (they count particles over all
    // ranks), so every rank must take the same branch.
    int changes = (off_rank ? 1 : 0) | (removals.empty() ? 0 : 2);
    if (Utilities::MPI::n_mpi_processes(comm) > 1)
      MPI_Allreduce(MPI_IN_PLACE, &changes, 1, MPI_INT, MPI_BOR, comm);
    if (changes & 1)
      {
        particles.sort_particles_into_subdomains_and_cells();
        ++n_full_sorts;
      }
    else if (changes & 2)
      particles.update_cached_numbers();

    return Utilities::MPI::sum(n_lost, comm);
  }


  template <int dim>
  std::string
  MaterialPoints<dim>::describe_leaving_point(
    const typename Particles::ParticleHandler<dim>::particle_iterator &p) const
  {
    std::ostringstream s;
    s << "material point " << p->get_id() << " of body "
      << p->get_properties()[fields.body] << " left the grid at ("
      << p->get_location() << ") with velocity ("
      << Fields::vector<dim>(p->get_properties().data() + fields.velocity)
      << "). Enlarge the grid, make its faces slip or fixed, or set "
         "'Simulation/out of grid = remove'.";
    return s.str();
  }


  template struct BodyParameters<1>;
  template struct BodyParameters<2>;
  template struct BodyParameters<3>;
  template class MaterialPoints<1>;
  template class MaterialPoints<2>;
  template class MaterialPoints<3>;
} // namespace mpm
