#include <deal.II/base/function_parser.h>
#include <deal.II/base/mpi.h>

#include <mpm/bodies/body_parameters.templates.h>
#include <mpm/material_points.h>
#include <mpm/parameters.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace mpm
{



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
  MaterialPoints<dim>::restore(const double minimum_point_mass)
  {
    particles.deserialize();
    minimum_mass = minimum_point_mass;
  }


  template <int dim>
  void
  MaterialPoints<dim>::reset_displacement_origin()
  {
    const unsigned int origin = fields.displacement_origin;
    if (origin == FieldLayout::absent)
      return;
    for (auto &p : particles)
      {
        const Point<dim> x = p.get_location();
        for (unsigned int d = 0; d < dim; ++d)
          p.get_properties()[origin + d] = x[d];
      }
  }


  template <int dim>
  std::string
  MaterialPoints<dim>::overlap_at(const unsigned int b,
                                  const Point<dim>  &x) const
  {
    for (unsigned int other = 0; other < body_list.size(); ++other)
      if (other != b && body_list[other].shape &&
          body_list[other].shape->contains(x))
        {
          std::ostringstream where;
          where << "overlaps 'Bodies/Body " << other << "' (the point at (" << x
                << ") lies in both); two bodies cannot fill the same "
                << "space unless 'Bodies/may overlap' is true";
          return InputError(body_list[b].name + "/shape",
                            body_list[b].shape_name,
                            where.str())
            .what();
        }
    return "";
  }


  template <int dim>
  void
  MaterialPoints<dim>::generate(const bool                   may_overlap,
                                const std::array<double, 2> &J_bounds)
  {
    this->J_bounds = J_bounds;
    std::string        overlap;
    const FieldLayout &l             = fields;
    bool               any_displaced = false;
    for (const auto &body : body_list)
      any_displaced = any_displaced || body.is_displaced();
    std::vector<Point<dim>> displaced_positions; // at t = 0, by local id
    std::vector<double>     p(l.n_properties);

    // The points go straight into deal.II's storage, reserved from a count
    // first: a copy of them, or a pool that grows by doubling, would set
    // the run's peak memory. The reserve has room for a quarter more: a
    // point that changes tile, or arrives from another rank, is copied
    // before its old slot is freed, and a pool at its capacity would
    // double (at its peak holding the old and the new array). Pages that
    // are reserved but never written take no memory.
    types::particle_index n_expected = 0;
    for (const unsigned int tile : grid.locally_owned_tiles())
      grid.for_each_cell_of_tile(tile, [&](const auto &, const Point<dim> &c) {
        for (const auto &body : body_list)
          n_expected += body.count_seeds(c);
      });
    particles.reserve(n_expected + n_expected / 4);
    types::particle_index n_local = 0;

    std::vector<types::particle_index> count(body_list.size(), 0);
    std::vector<double>                loaded_area(body_list.size(), 0.);
    minimum_mass = std::numeric_limits<double>::max();
    for (unsigned int b = 0; b < body_list.size(); ++b)
      {
        const auto &body = body_list[b];
        // The initial velocity and displacement are differentiated (APIC's
        // initial C_p = grad v0, the initial F = I + grad u0): a
        // fourth-order formula with a step of 1e-3 cells is exact for
        // affine fields up to round-off of about 1e-13.
        const auto differentiable = [&](const std::vector<std::string> &formula,
                                        const std::string              &entry) {
          auto f = Parse::vector_function<dim>(formula,
                                               body.constants,
                                               body.name + "/" + entry,
                                               1e-3 * grid.min_cell_size());
          f->set_formula(AutoDerivativeFunction<dim>::FourthOrder);
          return f;
        };
        const auto velocity =
          differentiable(body.initial_velocity, "initial velocity");
        std::unique_ptr<FunctionParser<dim>> displacement;
        if (body.is_displaced())
          displacement =
            differentiable(body.initial_displacement, "initial displacement");
        std::unique_ptr<FunctionParser<dim>> stress;
        if (body.is_prestressed())
          stress = Parse::vector_function<dim>(body.initial_stress,
                                               body.constants,
                                               body.name + "/initial stress");
        for (const unsigned int tile : grid.locally_owned_tiles())
          grid.for_each_cell_of_tile(
            tile, [&](const auto &cell, const Point<dim> &corner) {
              body.for_each_seed(
                corner,
                [&](const Point<dim>        &x,
                    const Point<dim>        &xi,
                    const double             volume,
                    const SurfaceShare<dim> &surface) {
                  if (!may_overlap && overlap.empty())
                    overlap = overlap_at(b, x);
                  const double mass = body.density * volume;
                  // The small-mass guard is about the deformable bodies: a
                  // rigid body's density must not move it (a light rigid
                  // floor changed the rolling disk on it).
                  if (!body.rigid_velocity)
                    minimum_mass = std::min(minimum_mass, mass);
                  // A deformable point's mass is divided by and squared:
                  // one near the smallest doubles makes its density
                  // infinite at the first step (a prescribed body's is
                  // never used so).
                  if (!body.rigid_velocity && !(mass >= 1e-150) &&
                      overlap.empty())
                    {
                      std::ostringstream why;
                      why << "gives a point at (" << x << ") a mass of " << mass
                          << " kg, below 1e-150: its density and energy "
                             "would overflow";
                      overlap = InputError(body.name + "/density",
                                           body.density_text,
                                           why.str())
                                  .what();
                    }
                  std::fill(p.begin(), p.end(), 0.);
                  p[l.mass]   = mass;
                  p[l.volume] = volume;
                  p[l.body]   = b;
                  for (unsigned int d = 0; d < dim; ++d)
                    p[l.velocity + d] = velocity->value(x, d);
                  // A speed whose square overflows is a typo, not physics:
                  // the first step would stop on a non-finite point.
                  if (overlap.empty() &&
                      !std::isfinite(Fields::vector<dim>(p.data() + l.velocity)
                                       .norm_square()))
                    {
                      std::ostringstream at;
                      at << "is infinite or overflows at (" << x
                         << "); give a finite velocity";
                      std::string given;
                      for (const auto &e : body.initial_velocity)
                        given += (given.empty() ? "" : "; ") + e;
                      overlap = InputError(body.name + "/initial velocity",
                                           given,
                                           at.str())
                                  .what();
                    }
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
                  if (l.displacement_origin != FieldLayout::absent)
                    for (unsigned int d = 0; d < dim; ++d)
                      p[l.displacement_origin + d] = x[d];
                  if (l.surface_area != FieldLayout::absent)
                    Fields::store(surface.area, p.data() + l.surface_area);
                  if (l.surface_offset != FieldLayout::absent)
                    Fields::store(surface.offset, p.data() + l.surface_offset);
                  loaded_area[b] += surface.area.norm();
                  initialise_state(body, stress.get(), x, p.data());
                  if (any_displaced)
                    displaced_positions.push_back(
                      displacement ? displace(*displacement, x, p.data()) : x);
                  // Numbered on this rank for now; made global below.
                  particles.insert_particle(x,
                                            grid.tile_reference(cell, xi),
                                            n_local++,
                                            grid.tile(tile),
                                            make_array_view(p));
                  ++count[b];
                });
            });
      }
    minimum_mass = Utilities::MPI::min(minimum_mass, comm);
    raise_if_any_failed(overlap, comm, true);
    raise_if_any_failed(state_failure, comm, true);

    for (unsigned int b = 0; b < body_list.size(); ++b)
      if (Utilities::MPI::sum(count[b], comm) == 0)
        throw InputError(body_list[b].name + "/particles per cell",
                         std::to_string(body_list[b].particles_per_cell),
                         "no material point falls inside the body: make it "
                         "larger than a cell or use more points per cell");
    for (unsigned int b = 0; b < body_list.size(); ++b)
      if (body_list[b].has_surface_loads() &&
          Utilities::MPI::sum(loaded_area[b], comm) == 0)
        throw InputError(body_list[b].name + (body_list[b].mesh_seeds
                                                ? "/pressure boundary ids"
                                                : "/loaded surface"),
                         body_list[b].loaded_surface,
                         "no material point of the body lies on its loaded "
                         "surface, so 'pressure' and 'traction' would act on "
                         "nothing");

    // Globally unique ids, numbered rank by rank.
    types::particle_index first = 0;
    MPI_Exscan(&n_local,
               &first,
               1,
               Utilities::MPI::mpi_type_id_for_type<types::particle_index>,
               MPI_SUM,
               comm);
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      first = 0; // MPI_Exscan leaves rank 0's result undefined
    if (first != 0)
      for (auto &point : particles)
        point.set_id(point.get_id() + first);
    particles.update_cached_numbers();

    // Displaced bodies: the points were put in the cells of their reference
    // positions; move them to where they start, then give them the stress
    // of their initial F.
    if (any_displaced)
      {
        for (auto &point : particles)
          point.set_location(displaced_positions[point.get_id() - first]);
        relocate(OutOfGridPolicy::stop);
        for (unsigned int b = 0; b < body_list.size(); ++b)
          if (body_list[b].is_displaced())
            body_list[b].material->update_stresses(
              particles, fields, b, 0., comm);
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
    // Raised collectively after generation (one rank alone must not stop).
    const auto note_failure = [&](const std::string &reason) {
      if (!state_failure.empty())
        return;
      std::ostringstream where;
      where << "the stress (" << sigma0 << ") at (" << x << ") " << reason;
      std::string text;
      for (const auto &e : body.initial_stress)
        text += (text.empty() ? "" : "; ") + e;
      state_failure =
        InputError(body.name + "/initial stress", text, where.str()).what();
    };
    if (!(sigma0.norm() <= largest_input))
      return note_failure("is infinite or beyond 1e15 Pa");
    try
      {
        body.material->initialise_point(properties, fields, sigma0);
      }
    catch (const std::domain_error &e)
      {
        return note_failure(std::string(e.what()) + " of '" +
                            body.material_name + "'");
      }
    // A stress-free state is one every model carries.
    if (stress == nullptr)
      return;
    try
      {
        check_initial_state(body, properties);
      }
    catch (const std::domain_error &e)
      {
        note_failure(e.what());
      }
  }


  template <int dim>
  void
  MaterialPoints<dim>::check_initial_state(const BodyParameters<dim> &body,
                                           const double *properties) const
  {
    // What the first step would stop on, blaming the time step, is caught
    // here where the input can be named: a stress too large for the
    // material's stiffness overflows its elastic strain (log strain:
    // exp(sigma / E)), and a fluid's density follows from its pressure.
    const std::string material = "'" + body.material_name + "'";
    const std::string stiffness =
      body.material->stiffness_parameters().empty()
        ? ""
        : ": the stress is too large for its stiffness, " +
            body.material->stiffness_parameters();
    bool finite = true;
    for (unsigned int i = 0; i < fields.n_properties; ++i)
      finite = finite && std::isfinite(properties[i]);
    if (!finite)
      throw std::domain_error("gives " + material +
                              " a state that is not finite" + stiffness);
    std::ostringstream s;
    const double energy = body.material->strain_energy(properties, fields);
    if (!std::isfinite(energy))
      {
        s << "gives " << material << " a strain energy of " << energy
          << stiffness;
        throw std::domain_error(s.str());
      }
    if (body.rigid_velocity)
      return;
    const double J =
      properties[fields.volume] * body.density / properties[fields.mass];
    if (!(J >= J_bounds[0] && J <= J_bounds[1]))
      {
        s << "gives " << material << " a volume ratio J = V / V0 = " << J
          << ", outside 'Simulation/J bounds' [" << J_bounds[0] << ", "
          << J_bounds[1] << "]" << stiffness;
        throw std::domain_error(s.str());
      }
  }


  template <int dim>
  Point<dim>
  MaterialPoints<dim>::displace(const FunctionParser<dim> &displacement,
                                const Point<dim>          &X,
                                double                    *properties)
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
    Point<dim>   reference;
    // Checked here, where the parameter is known: a point moved out of the
    // grid stopped the run as a point that left it, naming no parameter.
    std::ostringstream where;
    if (!std::isfinite(x.norm_square() + J))
      where << "is not finite at X = (" << X << ") or in its gradient there";
    else if (!(J > 0))
      where << "det(I + grad u0) = " << J << " <= 0 at X = (" << X
            << "): the initial displacement must not invert the body";
    else if (grid.locate(x, reference) == BackgroundGrid<dim>::invalid)
      where << "moves the point at X = (" << X << ") to (" << x
            << "), outside the grid";
    if (!where.str().empty())
      {
        const BodyParameters<dim> &body = body_list[properties[l.body]];
        std::string                text;
        for (const auto &e : body.initial_displacement)
          text += (text.empty() ? "" : "; ") + e;
        // Raised collectively after generation (one rank alone must not
        // stop).
        if (state_failure.empty())
          state_failure =
            InputError(body.name + "/initial displacement", text, where.str())
              .what();
        return X;
      }
    Fields::store(F, properties + l.deformation_gradient);
    properties[l.volume] *= J;
    return x;
  }


  template class MaterialPoints<1>;
  template class MaterialPoints<2>;
  template class MaterialPoints<3>;
} // namespace mpm
