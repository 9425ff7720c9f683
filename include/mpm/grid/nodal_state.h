#ifndef mpm_grid_nodal_state_h
#define mpm_grid_nodal_state_h

#include <deal.II/base/tensor.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <mpm/grid/nodal_layout.h>

#include <vector>

namespace mpm
{
  using namespace dealii;

  template <int dim>
  class BackgroundGrid;

  /**
   * The state the stages of a step share on the grid: the two nodal arrays
   * of NodalLayout and the velocity fields they hold per node. The
   * transfers write and read them, the grid update turns sums into
   * velocities, the faces, walls and contact correct those, substepping
   * rebuilds them; none of them owns the arrays, this class does. Output
   * reads a node's mass and velocity from it.
   */
  template <int dim>
  class NodalState
  {
  public:
    using Layout = NodalLayout<dim>;

    /// @p field_of_body: the velocity field of each body (all 0 with one
    /// field); @p body_slot: where a point's data holds its body index;
    /// @p mass_scaling: the factor the stored nodal masses carry;
    /// @p contact_data_per_field: the size of a field's contact data per
    /// node (0 without multi-body contact); @p fluid_forces: does a
    /// virtual fluid act?
    NodalState(const unsigned int        n_fields,
               std::vector<unsigned int> field_of_body,
               const unsigned int        body_slot,
               const double              mass_scaling,
               const unsigned int        contact_data_per_field = 0,
               const bool                fluid_forces           = false);

    /// (Re)create the arrays on @p grid's partition (after
    /// BackgroundGrid::repartition()).
    void
    reinit(const BackgroundGrid<dim> &grid);

    /// Offset of node @p node's field @p field in the arrays, in units of
    /// their per-field stride.
    unsigned int
    slot_of(const unsigned int node, const unsigned int field) const
    {
      return Layout::slot_of(node, field, n_fields);
    }

    /// The locally owned node fields (owned nodes times n_fields): the
    /// length, in strides, of the owned part of either array.
    unsigned int
    n_owned_slots() const
    {
      return owned_slots;
    }

    /// The field a point (its data @p q) scatters into and gathers from.
    unsigned int
    field_of(const double *q) const
    {
      return n_fields == 1
               ? 0
               : field_of_body[static_cast<unsigned int>(q[body_slot])];
    }

    /// Mass (without the mass scaling) and latest velocity (of the centre
    /// of mass of its fields) of locally owned node @p i.
    double
    mass(const unsigned int i) const;
    double
    velocity(const unsigned int i, const unsigned int d) const;

    /// Velocity fields per node: 1, or 1 + the bodies with their own.
    const unsigned int              n_fields;
    const std::vector<unsigned int> field_of_body;
    /// [m, mv, f] per node and field, summed over the ranks with
    /// compress(add).
    LinearAlgebra::distributed::Vector<double> sums;
    /// [m, v, v*] per node and field (mass, velocity before and after the
    /// force update), read through ghost values.
    LinearAlgebra::distributed::Vector<double> velocities;
    /// Multi-body contact only: per node and field, sum_p m_p grad
    /// phi_I(x_p) (dim values; minus the gradient of the field's nodal
    /// mass) and the number of the field's points whose domain holds the
    /// node, summed over the ranks; empty without.
    LinearAlgebra::distributed::Vector<double> contact_data;
    /// Virtual fluid only: the fluid's force at each node (dim values per
    /// node field, summed over the ranks; empty without) and its sum over
    /// the owned nodes, this step's.
    LinearAlgebra::distributed::Vector<double> fluid_force;
    Tensor<1, dim>                             fluid_force_total;

  private:
    const unsigned int body_slot;
    const double       mass_scaling;
    const unsigned int contact_data_per_field;
    const bool         fluid_forces;
    unsigned int       owned_slots = 0;
  };
} // namespace mpm

#endif
