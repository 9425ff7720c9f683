#ifndef mpm_boundary_conditions_face_kinds_h
#define mpm_boundary_conditions_face_kinds_h

// The kinds of grid face ('Grid/boundary x min', ...): their names and
// what the grid needs to know of them. What each does to the nodal
// velocities is GridFaces (grid_faces.cc): a new kind is a value, a name
// and a line in closes_the_grid (and is_rough, is_unilateral if they hold
// for it) here, and its rule there.
#include <mpm/options.h>

namespace mpm
{
  /// What a grid face does to the nodal velocity.
  enum class BoundaryType
  {
    free,     ///< nothing
    fixed,    ///< all velocity components zero
    slip,     ///< normal velocity component zero
    friction, ///< Coulomb contact: no penetration, free separation
    absorbing ///< viscous dashpots that let waves leave (Lysmer-Kuhlemeyer)
  };

  /// The face kinds by their names ('Grid/boundary x min', ...).
  inline const OptionTable<BoundaryType> boundary_names = {
    {"free", BoundaryType::free},
    {"fixed", BoundaryType::fixed},
    {"slip", BoundaryType::slip},
    {"friction", BoundaryType::friction},
    {"absorbing", BoundaryType::absorbing}};

  /// Does a face of kind @p kind close the grid, so that a point that
  /// crosses it is put back behind it (GridParameters::
  /// put_back_behind_closed_face), not lost?
  inline bool
  closes_the_grid(const BoundaryType kind)
  {
    return kind == BoundaryType::fixed || kind == BoundaryType::slip ||
           kind == BoundaryType::friction;
  }

  /// Does a face of kind @p kind hold the tangential velocity of its nodes
  /// (no-slip or Coulomb), where APIC's affine field can hide a point's
  /// motion from it (GridToParticle, Simulation's warning)?
  inline bool
  is_rough(const BoundaryType kind)
  {
    return kind == BoundaryType::fixed || kind == BoundaryType::friction;
  }

  /// Does a face of kind @p kind hold only what moves into it, so that
  /// the step must know where its nodes were pressed (GridFaces::apply)?
  inline bool
  is_unilateral(const BoundaryType kind)
  {
    return kind == BoundaryType::friction;
  }
} // namespace mpm

#endif
