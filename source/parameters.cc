#include <deal.II/base/utilities.h>

#include <deal.II/lac/vector.h>

#include <mpm/parameters.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>

namespace mpm
{
  InputError::InputError(const std::string &parameter,
                         const std::string &value,
                         const std::string &allowed)
    : std::runtime_error("parameter '" + parameter + "' = '" + value +
                         "': " + allowed)
  {
  }


  InputError::InputError(const std::string &message)
    : std::runtime_error(message)
  {
  }


  void
  raise_if_any_failed(const std::string &local_diagnosis,
                      MPI_Comm           comm,
                      const bool         input_error)
  {
    auto raise = [input_error](const std::string &message) {
      if (input_error)
        throw InputError(message);
      throw RunError(message);
    };
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
    if (n_ranks == 1)
      {
        if (!local_diagnosis.empty())
          raise(local_diagnosis);
        return;
      }
    const unsigned int first =
      Utilities::MPI::min(local_diagnosis.empty()
                            ? n_ranks
                            : Utilities::MPI::this_mpi_process(comm),
                          comm);
    if (first == n_ranks)
      return;
    raise(Utilities::MPI::broadcast(comm, local_diagnosis, first));
  }


  double
  multiple_of(const double k, const double interval)
  {
    char decimal[32];
    std::snprintf(decimal, sizeof(decimal), "%.15g", k * interval);
    return std::strtod(decimal, nullptr);
  }


  double
  multiple_after(const double t, const double interval)
  {
    return multiple_of(std::floor(t / interval * (1 + 1e-12)) + 1, interval);
  }


  namespace Parse
  {
    namespace
    {
      std::string
      join(const std::string &path, const std::string &name)
      {
        return path.empty() ? name : path + "/" + name;
      }


      std::string
      format(const double x)
      {
        std::ostringstream s;
        s << x;
        return s.str();
      }
    } // namespace


    double
    number(const std::string &text)
    {
      const std::string s = Utilities::trim(text);
      char             *end;
      const double      value = std::strtod(s.c_str(), &end);
      if (s.empty() || end != s.c_str() + s.size())
        throw std::invalid_argument("'" + text + "' is not a number");
      return value;
    }


    std::string
    given(const ParameterHandler &prm,
          const std::string      &path,
          const std::string      &name)
    {
      return "'" + join(path, name) + "' = '" + prm.get(name) + "'";
    }


    std::map<std::string, std::string>
    entries(const ParameterHandler &prm)
    {
      std::ostringstream listing;
      prm.print_parameters(listing, ParameterHandler::ShortPRM);
      std::istringstream                 lines(listing.str());
      std::vector<std::string>           path;
      std::map<std::string, std::string> found;
      std::string                        line;
      while (std::getline(lines, line))
        {
          line = Utilities::trim(line);
          if (line.rfind("subsection ", 0) == 0)
            path.push_back(Utilities::trim(line.substr(11)));
          else if (line == "end" && !path.empty())
            path.pop_back();
          else if (line.rfind("set ", 0) == 0)
            {
              const auto  equals = line.find('=');
              std::string p;
              for (const auto &section : path)
                p += section + "/";
              found[p + Utilities::trim(line.substr(4, equals - 4))] =
                equals == std::string::npos
                  ? ""
                  : Utilities::trim(line.substr(equals + 1));
            }
        }
      return found;
    }


    std::string
    one_line(const ExceptionBase &e)
    {
      std::ostringstream s;
      e.print_info(s);
      return Utilities::trim(
        std::regex_replace(s.str(), std::regex("\\s+"), " "));
    }


    void
    set_entry(ParameterHandler  &prm,
              const std::string &path,
              const std::string &value)
    {
      const auto   parts = Utilities::split_string_list(path, '/');
      unsigned int depth = 0;
      std::string  problem;
      try
        {
          for (; depth + 1 < parts.size(); ++depth)
            prm.enter_subsection(parts[depth]);
          // set() throws (in Release and Debug builds alike) for an entry
          // that is not declared or a value that does not fit its pattern.
          prm.set(parts.back(), value);
        }
      catch (const ExceptionBase &e)
        {
          problem = one_line(e);
        }
      for (unsigned int i = 0; i < depth; ++i)
        prm.leave_subsection();
      if (!problem.empty())
        throw InputError(path, value, problem);
    }


    namespace
    {
      /// Levenshtein distance, case-blind: how far a misspelt path is from
      /// a declared one.
      unsigned int
      edit_distance(const std::string &a, const std::string &b)
      {
        std::vector<unsigned int> row(b.size() + 1);
        for (unsigned int j = 0; j <= b.size(); ++j)
          row[j] = j;
        for (unsigned int i = 1; i <= a.size(); ++i)
          {
            unsigned int diagonal = row[0];
            row[0]                = i;
            for (unsigned int j = 1; j <= b.size(); ++j)
              {
                const unsigned int up = row[j];
                const bool         same =
                  std::tolower(a[i - 1]) == std::tolower(b[j - 1]);
                row[j] = std::min(
                  {row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0u : 1u)});
                diagonal = up;
              }
          }
        return row[b.size()];
      }
    } // namespace


    std::string
    did_you_mean(const std::string                        &path,
                 const std::map<std::string, std::string> &declared)
    {
      std::vector<std::pair<unsigned int, std::string>> near;
      for (const auto &d : declared)
        near.emplace_back(edit_distance(path, d.first), d.first);
      std::sort(near.begin(), near.end());
      std::string        suggestions;
      const unsigned int reach = std::max<unsigned int>(3, path.size() / 4);
      for (unsigned int i = 0; i < 3 && i < near.size(); ++i)
        if (near[i].first <= reach)
          suggestions +=
            (suggestions.empty() ? "'" : ", '") + near[i].second + "'";
      return suggestions.empty() ? "" : "; did you mean " + suggestions + "?";
    }


    double
    bounded_double(const ParameterHandler &prm,
                   const std::string      &path,
                   const std::string      &name,
                   const double            lower,
                   const double            upper,
                   const bool              lower_open,
                   const bool              upper_open)
    {
      const std::string text = prm.get(name);
      double            value;
      try
        {
          value = number(text);
        }
      catch (...)
        {
          throw InputError(join(path, name), text, "must be a number");
        }
      const bool too_low  = lower_open ? !(value > lower) : !(value >= lower);
      const bool too_high = upper_open ? !(value < upper) : !(value <= upper);
      if (too_low || too_high || !std::isfinite(value))
        {
          // Half-open ranges read better as an inequality.
          const std::string allowed =
            upper >= 1e300 ? std::string("must be ") +
                               (lower_open ? "> " : ">= ") + format(lower)
                           : std::string("allowed range is ") +
                               (lower_open ? "(" : "[") + format(lower) + ", " +
                               format(upper) + (upper_open ? ")" : "]");
          throw InputError(join(path, name), text, allowed);
        }
      return value;
    }


    std::vector<double>
    double_list(const ParameterHandler &prm,
                const std::string      &path,
                const std::string      &name,
                const unsigned int      n)
    {
      const std::string   text    = prm.get(name);
      const auto          entries = Utilities::split_string_list(text, ',');
      std::vector<double> values;
      try
        {
          for (const auto &e : entries)
            values.push_back(number(e));
        }
      catch (...)
        {
          throw InputError(join(path, name),
                           text,
                           "must be a comma-separated list of numbers");
        }
      for (const double v : values)
        if (!(std::abs(v) <= largest_input))
          throw InputError(join(path, name),
                           text,
                           "must be finite numbers of magnitude up to 1e15");
      if (values.empty())
        throw InputError(join(path, name),
                         text,
                         "is empty: give " + std::to_string(n) +
                           " comma-separated numbers (or one for all)");
      if (values.size() == 1)
        values.assign(n, values[0]);
      else if (values.size() != n)
        throw InputError(join(path, name),
                         text,
                         "expects " + std::to_string(n) +
                           " comma-separated values (one per dimension) or "
                           "a single value for all");
      return values;
    }


    template <int dim>
    Point<dim>
    point(const ParameterHandler &prm,
          const std::string      &path,
          const std::string      &name)
    {
      const auto v = double_list(prm, path, name, dim);
      Point<dim> p;
      for (unsigned int d = 0; d < dim; ++d)
        p[d] = v[d];
      return p;
    }


    template <int dim>
    Tensor<1, dim>
    vector(const ParameterHandler &prm,
           const std::string      &path,
           const std::string      &name)
    {
      return point<dim>(prm, path, name);
    }


    std::vector<std::string>
    expression_list(const ParameterHandler &prm,
                    const std::string      &name,
                    const unsigned int      n,
                    const std::string      &path)
    {
      const std::string text        = prm.get(name);
      auto              expressions = Utilities::split_string_list(text, ';');
      if (expressions.empty())
        expressions.assign(n, "0");
      else if (expressions.size() == 1)
        expressions.assign(n, expressions[0]);
      else if (expressions.size() != n)
        throw InputError(join(path, name),
                         text,
                         "expects " + std::to_string(n) +
                           " expressions separated by ';' (one per "
                           "dimension) or a single expression for all");
      return expressions;
    }


    std::vector<bool>
    body_flags(const ParameterHandler &prm,
               const std::string      &path,
               const std::string      &name,
               const unsigned int      n_bodies,
               const bool              empty_means)
    {
      const std::string list = prm.get(name);
      std::vector<bool> flags(n_bodies, list.empty() && empty_means);
      for (const auto &item : Utilities::split_string_list(list, ','))
        {
          int b = -1;
          try
            {
              b = Utilities::string_to_int(item);
            }
          catch (...)
            {
            }
          if (b < 0 || b >= static_cast<int>(n_bodies))
            throw InputError(path + "/" + name,
                             list,
                             "must be comma-separated body indices in [0, " +
                               std::to_string(n_bodies) + ")");
          flags[b] = true;
        }
      return flags;
    }


    bool
    is_zero(const std::vector<std::string> &expressions)
    {
      for (const auto &e : expressions)
        {
          try
            {
              if (number(e) != 0.)
                return false;
            }
          catch (...)
            {
              return false;
            }
        }
      return true;
    }


    std::map<std::string, double>
    constants(ParameterHandler &prm)
    {
      prm.enter_subsection("Simulation");
      const std::string text = prm.get("constants");
      prm.leave_subsection();
      std::map<std::string, double> c = {{"pi", numbers::PI}};
      // The names an expression already knows: the coordinates and time.
      const std::set<std::string> taken = {"pi", "x", "y", "z", "t"};
      for (const auto &entry : Utilities::split_string_list(text, ','))
        {
          const auto  eq   = entry.find('=');
          std::string name = Utilities::trim(entry.substr(0, eq));
          try
            {
              if (eq == std::string::npos || name.empty())
                throw 0;
              const double value =
                number(Utilities::trim(entry.substr(eq + 1)));
              if (!std::isfinite(value))
                throw 0;
              if (taken.count(name) > 0 || c.count(name) > 0)
                throw InputError("Simulation/constants",
                                 text,
                                 "defines '" + name +
                                   "' again (pi, x, y, z, t and each "
                                   "constant have one meaning)");
              c[name] = value;
            }
          catch (const InputError &)
            {
              throw;
            }
          catch (...)
            {
              throw InputError("Simulation/constants",
                               text,
                               "must be a comma-separated list of name=number");
            }
        }
      return c;
    }


    template <int dim>
    std::unique_ptr<FunctionParser<dim>>
    vector_function(const std::vector<std::string>      &expressions,
                    const std::map<std::string, double> &constants,
                    const std::string                   &parameter,
                    const double                         difference_step)
    {
      auto f = std::make_unique<FunctionParser<dim>>(expressions.size(),
                                                     0.,
                                                     difference_step);
      // As given: one expression stands for every component.
      std::string text;
      for (const auto &e : expressions)
        text += (text.empty() ? "" : "; ") + e;
      if (std::all_of(expressions.begin(),
                      expressions.end(),
                      [&](const std::string &e) {
                        return e == expressions[0];
                      }))
        text = expressions.empty() ? "" : expressions[0];
      // muparser reads 'a, b' as two results and keeps the last: a vector
      // written with commas would silently become one component.
      for (const auto &e : expressions)
        {
          int depth = 0;
          for (const char c : e)
            {
              depth += (c == '(') - (c == ')');
              if (c == ',' && depth == 0)
                throw InputError(parameter,
                                 text,
                                 "has a ',' outside parentheses; the "
                                 "components of a vector are separated by ';'");
            }
        }
      // deal.II prints muparser's diagnosis to std::cerr before it throws;
      // capture it so that the user gets one line, with its gist.
      std::ostringstream captured;
      std::streambuf    *cerr_buffer = std::cerr.rdbuf(captured.rdbuf());
      std::string        problem;
      try
        {
          f->initialize(FunctionParser<dim>::default_variable_names() + ",t",
                        expressions,
                        constants,
                        true);
          // muparser reports unknown names only on first evaluation.
          Vector<double> value(expressions.size());
          f->vector_value(Point<dim>(), value);
        }
      catch (...)
        {
          problem = "is not a valid expression in x, y, z, t and the names "
                    "of 'Simulation/constants'";
          const std::string text_seen = captured.str();
          const auto        m         = text_seen.find("Message:");
          if (m != std::string::npos)
            problem +=
              " (" +
              Utilities::trim(
                text_seen.substr(m + 8, text_seen.find('\n', m) - m - 8)) +
              ")";
        }
      std::cerr.rdbuf(cerr_buffer);
      if (!problem.empty())
        throw InputError(parameter, text, problem);
      return f;
    }


    template std::unique_ptr<FunctionParser<1>>
    vector_function<1>(const std::vector<std::string> &,
                       const std::map<std::string, double> &,
                       const std::string &,
                       const double);
    template std::unique_ptr<FunctionParser<2>>
    vector_function<2>(const std::vector<std::string> &,
                       const std::map<std::string, double> &,
                       const std::string &,
                       const double);
    template std::unique_ptr<FunctionParser<3>>
    vector_function<3>(const std::vector<std::string> &,
                       const std::map<std::string, double> &,
                       const std::string &,
                       const double);
    template Point<1>
    point<1>(const ParameterHandler &,
             const std::string &,
             const std::string &);
    template Point<2>
    point<2>(const ParameterHandler &,
             const std::string &,
             const std::string &);
    template Point<3>
    point<3>(const ParameterHandler &,
             const std::string &,
             const std::string &);
    template Tensor<1, 1>
    vector<1>(const ParameterHandler &,
              const std::string &,
              const std::string &);
    template Tensor<1, 2>
    vector<2>(const ParameterHandler &,
              const std::string &,
              const std::string &);
    template Tensor<1, 3>
    vector<3>(const ParameterHandler &,
              const std::string &,
              const std::string &);
  } // namespace Parse
} // namespace mpm
