#ifndef mpm_boundary_conditions_grid_faces_h
#define mpm_boundary_conditions_grid_faces_h

#include <mpm/background_grid.h>
#include <mpm/bodies/body_parameters.h>
#include <mpm/work_account.h>

#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * The grid's faces acting on the nodal velocities: each face kind of
   * 'Grid/boundary' (BoundaryType) is a rule on the velocity of the nodes
   * on that face, applied to every velocity field of a node alike, after
   * each transfer to the grid and after the force update:
   *
   * - fixed, slip: the components the face holds are set to zero;
   * - friction: Coulomb contact, a velocity into the face is removed and
   *   friction takes at most mu times that from the tangential velocity;
   *   the nodes it pressed at the force update keep their normal
   *   velocity 0 in MUSL's strain-rate velocities (apply());
   * - absorbing: a dashpot rho c on the normal and the tangential
   *   components (Lysmer-Kuhlemeyer), only at the force update.
   *
   * A face kind is defined here: which of the owned nodes it holds
   * (reinit()) and its rule on their velocities (apply()); a new one adds
   * a value and a name to BoundaryType and boundary_names (face_kinds.h).
   */
  template <int dim>
  class GridFaces
  {
  public:
    /// Takes the absorbing faces' impedances from the body
    /// 'Grid/absorbing body' of @p bodies (checked, if a face absorbs).
    GridFaces(const BackgroundGrid<dim>              &grid,
              const std::vector<BodyParameters<dim>> &bodies);

    /// List the owned nodes on each face with what the face does to them
    /// (after the grid's partition changed; faces of each kind combine at
    /// edges and corners).
    void
    reinit();

    /**
     * Apply every face's rule to the nodal velocities at @p slot (an
     * offset in a node's entry of NodalLayout::n_velocities values) of
     * the @p n_fields fields of each node, in the interleaved array @p u.
     * @p dt > 0 at the force update, where the dashpots act. With @p work
     * (only at the force update, @p slot v_new), the work of each rule's
     * impulses goes to its sum (WorkAccount::face_friction,
     * face_constraint), at the mean of the node's velocities at the
     * step's start and end.
     *
     * @p for_strain_rate: MUSL's strain-rate velocities, transferred anew
     * after the force update. A friction face holds only what moves into
     * it, so it would let a node go that it held at the force update if
     * the transferred velocity now leaves the face. A body that presses
     * on the face pushes its nodes there into it by its stress and gets
     * the face's reaction back; a strain rate that sees those nodes leave
     * with the body's velocity is 0, so the stress that pushed does not
     * relax: a lone point, all of whose nodes carry its own velocity, was
     * thrown off the face again and again by a stress that each landing
     * made larger (benchmarks/slope/README.md). So where the face pressed
     * at this step's force update, the normal velocity stays 0 here, as
     * USL's strain rate sees it (the same rule as deformable contact's,
     * GridUpdate::apply_contact).
     */
    void
    apply(double            *u,
          const unsigned int n_fields,
          const unsigned int slot,
          const double       dt,
          WorkAccount       *work            = nullptr,
          const bool         for_strain_rate = false);

    /**
     * Take out of the contact data @p data (@p per_field values for each
     * of the @p n_fields fields of a node, a mass gradient first, see
     * MultiFieldContact) the component normal to each face that closes
     * the grid at the node. A body's mass gradient at a node on such a face
     * leans out of it because the grid ends there, not because the body's
     * surface turns: a face that closes the grid is a wall or a mirror,
     * and a mirrored body has no gradient across it. Left in, a rigid
     * footing's normal at its corner on the symmetry face tilted, the
     * contact held the soil there only in part, and the point trapped
     * under the corner was pumped to 8.6 m/s (pure FLIP; MUSL stopped on
     * the energy guard at t = 0.4 s; benchmarks/plasticity/README.md).
     */
    void
    keep_contact_normals_in_faces(double            *data,
                                  const unsigned int n_fields,
                                  const unsigned int per_field) const;

    /// Does any face of the grid of @p prm hold only what moves into it
    /// (a friction face, is_unilateral())?
    static bool
    has_unilateral_face(const GridParameters<dim> &prm);

    /// Coulomb contact of the nodal velocity @p v with grid face @p face
    /// (f = x min, x max, y min, ...) of friction coefficient @p mu; true
    /// if the velocity moved into the face (the face pressed).
    static bool
    apply_coulomb_contact(double *v, const unsigned int face, const double mu);

  private:
    /// Coulomb contact of the velocity in @p slot of the node @p node
    /// (its entry of NodalLayout::n_velocities values) with @p face; with
    /// @p work, the work of the normal impulse (a constraint's) and of the
    /// tangential one (friction's); true if the face pressed.
    static bool
    coulomb_contact_of_node(double            *node,
                            const unsigned int slot,
                            const unsigned int face,
                            const double       mu,
                            WorkAccount       *work);

    /// A node on an absorbing face: the face (x min, x max, y min, ...)
    /// and the share of its area the node's dashpots act on.
    struct AbsorbingNode
    {
      unsigned int node, face;
      double       area;
    };

    const BackgroundGrid<dim> &grid;
    /// Impedances rho c_p and rho c_s of the absorbing faces.
    double normal_impedance = 0, shear_impedance = 0;
    /// Owned nodes on fixed and slip faces and the bit mask of the
    /// velocity components they hold at zero.
    std::vector<std::pair<unsigned int, unsigned int>> constrained_nodes;
    /// Owned nodes on friction faces and the bit mask of those faces
    /// (bit f: face f = x min, x max, y min, ...).
    std::vector<std::pair<unsigned int, unsigned int>> friction_nodes;
    /// For each entry of friction_nodes and each field, the faces that
    /// pressed at the last force update (bit f: face f), for MUSL's
    /// strain-rate velocities of the same step.
    std::vector<unsigned int> pressed_faces;
    /// Owned nodes on absorbing faces, one entry per node and face.
    std::vector<AbsorbingNode> absorbing_nodes;
    /// Owned nodes on faces that close the grid (closes_the_grid) and the
    /// bit mask of those faces' normal directions.
    std::vector<std::pair<unsigned int, unsigned int>> closed_face_nodes;
  };
} // namespace mpm

#endif
