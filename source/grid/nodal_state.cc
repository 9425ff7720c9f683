#include <mpm/background_grid.h>
#include <mpm/grid/nodal_state.h>

#include <utility>

namespace mpm
{
  template <int dim>
  NodalState<dim>::NodalState(const unsigned int        n_fields,
                              std::vector<unsigned int> field_of_body,
                              const unsigned int        body_slot,
                              const double              mass_scaling,
                              const unsigned int        contact_data_per_field,
                              const bool                fluid_forces)
    : n_fields(n_fields)
    , field_of_body(std::move(field_of_body))
    , body_slot(body_slot)
    , mass_scaling(mass_scaling)
    , contact_data_per_field(contact_data_per_field)
    , fluid_forces(fluid_forces)
  {
  }


  template <int dim>
  void
  NodalState<dim>::reinit(const BackgroundGrid<dim> &grid)
  {
    sums.reinit(grid.make_partitioner(n_fields * Layout::n_sums));
    velocities.reinit(grid.make_partitioner(n_fields * Layout::n_velocities));
    owned_slots = n_fields * grid.n_locally_owned_nodes();
    if (contact_data_per_field > 0)
      contact_data.reinit(
        grid.make_partitioner(n_fields * contact_data_per_field));
    if (fluid_forces)
      fluid_force.reinit(grid.make_partitioner(n_fields * dim));
  }


  template <int dim>
  double
  NodalState<dim>::mass(const unsigned int i) const
  {
    double m = 0;
    for (unsigned int f = 0; f < n_fields; ++f)
      m += velocities.local_element(Layout::n_velocities * slot_of(i, f) +
                                    Layout::node_mass);
    return m / mass_scaling;
  }


  template <int dim>
  double
  NodalState<dim>::velocity(const unsigned int i, const unsigned int d) const
  {
    double m = 0, p = 0;
    for (unsigned int f = 0; f < n_fields; ++f)
      {
        const double *node =
          velocities.begin() + Layout::n_velocities * slot_of(i, f);
        m += node[Layout::node_mass];
        p += node[Layout::node_mass] * node[Layout::v_new + d];
      }
    return m > 0 ? p / m : 0.;
  }


  template class NodalState<1>;
  template class NodalState<2>;
  template class NodalState<3>;
} // namespace mpm
