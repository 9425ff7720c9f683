#ifndef mpm_transfer_gather_state_h
#define mpm_transfer_gather_state_h

namespace mpm
{
  /// What a transfer's gather (G2P) reads besides the point, its stencil
  /// and the nodal velocities: the same for every point of a step.
  struct GatherState
  {
    /// The step: APIC carries C_p over it (advected_affine_velocity).
    double dt;
    /// PIC/FLIP: alpha, the FLIP share of this step (0 = PIC, 1 = FLIP).
    double flip_fraction;
    /// PIC/FLIP with Newmark's gamma != 1/2 (USL): the nodes hold
    /// v_old + (gamma + 1/2) dt a, and the velocity update is
    /// increment_factor = 1 / (gamma + 1/2) times their increment.
    bool   newmark;
    double increment_factor;
    /// APIC with the linear basis: the small-mass threshold of the nodes
    /// (with the mass scaling), see discount_light_node_increments.
    double light_mass;
  };
} // namespace mpm

#endif
