#ifndef mpm_options_h
#define mpm_options_h

#include <deal.II/base/exceptions.h>

#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

namespace mpm
{
  /**
   * One family of options (update scheme, basis, transfer, face kind, ...):
   * each name and the value it stands for, written once. The table gives
   * Patterns::Selection its list when the entry is declared and turns the
   * chosen name into the value when it is parsed, so that a new option is
   * one line here and a name can never be declared and parsed differently.
   */
  template <typename Value>
  class OptionTable
  {
  public:
    OptionTable(std::initializer_list<std::pair<std::string, Value>> entries)
      : entries(entries)
    {
    }

    /// The names joined by '|', as Patterns::Selection takes them.
    std::string
    selection() const
    {
      std::string list;
      for (const auto &[name, value] : entries)
        list += (list.empty() ? "" : "|") + name;
      return list;
    }

    /// The value of @p name, which ParameterHandler has already checked
    /// against selection().
    Value
    value(const std::string &name) const
    {
      for (const auto &[n, v] : entries)
        if (n == name)
          return v;
      AssertThrow(false, dealii::ExcMessage("unknown option '" + name + "'"));
      return entries.front().second;
    }

    /// The name of @p value, for messages.
    const std::string &
    name(const Value value) const
    {
      for (const auto &[n, v] : entries)
        if (v == value)
          return n;
      AssertThrow(false, dealii::ExcInternalError());
      return entries.front().first;
    }

  private:
    std::vector<std::pair<std::string, Value>> entries;
  };
} // namespace mpm

#endif
