#ifndef mpm_transfer_transfers_h
#define mpm_transfer_transfers_h

#include <mpm/integrator_parameters.h>
#include <mpm/transfer/apic.h>
#include <mpm/transfer/flip_pic.h>

namespace mpm
{
  /**
   * Call @p f with the transfer class of @p transfer (an object of it): as
   * with_basis() does for the basis, everything in @p f is compiled for
   * each transfer, and the choice is made once, outside the point loops.
   * A new transfer is its header, a value and a name in Transfer and
   * transfer_names (integrator_parameters.h), and a line here.
   */
  template <typename F>
  inline decltype(auto)
  with_transfer(const Transfer transfer, F &&f)
  {
    switch (transfer)
      {
        case Transfer::apic:
          return f(AffineParticleInCell());
        default:
          return f(FlipPicBlend());
      }
  }
} // namespace mpm

#endif
