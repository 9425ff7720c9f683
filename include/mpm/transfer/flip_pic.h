#ifndef mpm_transfer_flip_pic_h
#define mpm_transfer_flip_pic_h

#include <deal.II/base/tensor.h>

#include <mpm/field_layout.h>
#include <mpm/transfer/gather_state.h>

#include <array>

namespace mpm
{
  using namespace dealii;

  /**
   * The PIC/FLIP blend ('Simulation/transfer = FLIP'): a point gives the
   * nodes its velocity, and takes back alpha (v_p + dv) + (1 - alpha) v,
   * the FLIP update by the grid's velocity increment dv blended with the
   * PIC one, the grid velocity v at the point (alpha = 'FLIP fraction',
   * or exp(-dt / 'PIC relaxation time'): a share per step damps more the
   * smaller the step, a rate does not; IntegratorParameters).
   *
   * A transfer is a class with the members below, chosen at compile time
   * like the basis (with_transfer()): the scatter and the gather are
   * compiled once for each, so the loops of one carry nothing of another.
   */
  struct FlipPicBlend
  {
    /// Its name in 'Simulation/transfer'.
    static constexpr const char *name = "FLIP";

    /// Does the transfer blend PIC into its update ('FLIP fraction',
    /// 'PIC relaxation time')?
    static constexpr bool blends_pic = true;

    /// Does the transfer keep an affine velocity C_p per point?
    static constexpr bool stores_affine_velocity = false;

    /// Does the gather read the grid's velocity increment at the point,
    /// sum_I phi_I (v_new - v_old)_I?
    template <typename Basis>
    static constexpr bool
    needs_increment()
    {
      return true;
    }

    /// P2G: what of the point's momentum is not m_p v_p (here nothing).
    template <int dim>
    static Tensor<2, dim>
    affine_momentum(const double, const double *, const FieldLayout &)
    {
      return {};
    }

    /// P2G: the momentum the point gives stencil node @p v.
    template <int dim, typename Stencil>
    static Tensor<1, dim>
    momentum_at_node(const Tensor<1, dim> &mv,
                     const Tensor<2, dim> &,
                     const Stencil &,
                     const unsigned int)
    {
      return mv;
    }

    /**
     * G2P: the point's new velocity from the grid velocity @p v_grid and
     * increment @p dv_grid at it (the position and the kinematics are the
     * gather's, the same for every transfer).
     */
    template <int dim, typename Basis>
    static void
    update_point(const Basis &,
                 const typename Basis::Stencil &,
                 const double *,
                 const unsigned int,
                 double               *q,
                 const FieldLayout    &l,
                 const Tensor<1, dim> &v_grid,
                 const Tensor<1, dim> &dv_grid,
                 const GatherState    &c,
                 std::array<Tensor<1, dim>, Basis::n_nodes> &)
    {
      const double         alpha = c.flip_fraction;
      const Tensor<1, dim> v_p   = Fields::vector<dim>(q + l.velocity);
      if (c.newmark)
        {
          // The nodes hold v_old + (gamma + 1/2) dt a: the velocity
          // update is dt a of it.
          const Tensor<1, dim> dv = c.increment_factor * dv_grid;
          Fields::store(Tensor<1, dim>(alpha * (v_p + dv) +
                                       (1. - alpha) * (v_grid - dv_grid + dv)),
                        q + l.velocity);
        }
      else
        Fields::store(Tensor<1, dim>(alpha * (v_p + dv_grid) +
                                     (1. - alpha) * v_grid),
                      q + l.velocity);
    }
  };
} // namespace mpm

#endif
