// What the unit tests share: a check that prints what it measured against
// its bound, and the verdict of them all.
#ifndef mpm_tests_checks_h
#define mpm_tests_checks_h

#include <cmath>
#include <iostream>
#include <string>

namespace checks
{
  inline bool all_ok = true;

  /// |value| <= bound.
  inline void
  check(const std::string &what, const double value, const double bound)
  {
    const bool ok = std::abs(value) <= bound;
    std::cout << (ok ? "  ok   " : "  FAIL ") << what << ": " << value
              << " (bound " << bound << ")" << std::endl;
    all_ok = all_ok && ok;
  }

  inline void
  check_true(const std::string &what, const bool value)
  {
    std::cout << (value ? "  ok   " : "  FAIL ") << what << std::endl;
    all_ok = all_ok && value;
  }
} // namespace checks

#endif
