#ifndef mpm_grid_nodal_layout_h
#define mpm_grid_nodal_layout_h

namespace mpm
{
  /**
   * The layout of the step's two nodal arrays, shared by every stage that
   * reads or writes them (transfers, grid update, grid faces, contact,
   * substepping). Each node holds its velocity fields one after the other
   * (1, or 1 + the bodies with a field of their own): field f of node i
   * starts at entry (n_fields i + f) times the stride below.
   *
   * - the sums, [m, mv (dim), f (dim)], are what the points scatter and
   *   are added over the ranks (compress(add));
   * - the velocities, [m, v_old (dim), v_new (dim)], are the mass (with the
   *   mass scaling) and the velocity before and after the force update,
   *   read by the points through ghost values.
   */
  template <int dim>
  struct NodalLayout
  {
    static constexpr unsigned int mass = 0, momentum = 1, force = 1 + dim;
    static constexpr unsigned int n_sums    = 1 + 2 * dim;
    static constexpr unsigned int node_mass = 0, v_old = 1, v_new = 1 + dim;
    static constexpr unsigned int n_velocities = 1 + 2 * dim;

    /// Offset of node @p node's field @p field, in units of the stride.
    static unsigned int
    slot_of(const unsigned int node,
            const unsigned int field,
            const unsigned int n_fields)
    {
      return n_fields * node + field;
    }
  };
} // namespace mpm

#endif
