#ifndef mpm_transfer_transfers_h
#define mpm_transfer_transfers_h

#include <mpm/options.h>
#include <mpm/transfer/apic.h>
#include <mpm/transfer/flip_pic.h>

#include <string>
#include <utility>

namespace mpm
{
  /// A list of transfer classes.
  template <typename... T>
  struct TransferList
  {
  };

  /**
   * Every transfer of the program, in the order 'Simulation/transfer'
   * lists their names. A new transfer is its header (a class with the
   * members of FlipPicBlend, its name among them) and a line here: its
   * name, the parameter's list and the dispatch below all follow.
   */
  using Transfers = TransferList<FlipPicBlend, AffineParticleInCell>;

  /// A transfer: its place in Transfers.
  enum class Transfer : unsigned int
  {
  };

  namespace internal
  {
    template <typename... T>
    OptionTable<Transfer>
    transfer_table(TransferList<T...>)
    {
      unsigned int i = 0;
      // A braced list is evaluated left to right: the names in order.
      return {{std::string(T::name), Transfer{i++}}...};
    }

    template <typename F, typename First, typename... Rest>
    decltype(auto)
    with_transfer_at(const unsigned int index,
                     F                &&f,
                     TransferList<First, Rest...>)
    {
      if constexpr (sizeof...(Rest) == 0)
        return f(First());
      else
        {
          if (index == 0)
            return f(First());
          return with_transfer_at(index - 1,
                                  std::forward<F>(f),
                                  TransferList<Rest...>());
        }
    }
  } // namespace internal

  /// The transfers by their names ('Simulation/transfer').
  inline const OptionTable<Transfer> transfer_names =
    internal::transfer_table(Transfers());

  /**
   * Call @p f with the transfer class of @p transfer (an object of it): as
   * with_basis() does for the basis, everything in @p f is compiled for
   * each transfer, and the choice is made once, outside the point loops.
   * What a scene's transfer is or does is asked the same way, of its
   * class: with_transfer(t, [](auto c) { return c.stores_affine_velocity;
   * }).
   */
  template <typename F>
  inline decltype(auto)
  with_transfer(const Transfer transfer, F &&f)
  {
    return internal::with_transfer_at(static_cast<unsigned int>(transfer),
                                      std::forward<F>(f),
                                      Transfers());
  }
} // namespace mpm

#endif
