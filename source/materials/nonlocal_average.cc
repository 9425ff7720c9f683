// The nonlocal average of a point value over a body's points (damage's
// driving strain, softening's plastic strain), and its parameters.
#include <deal.II/base/mpi.templates.h>

#include <mpm/materials/nonlocal_average.h>
#include <mpm/parameters.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <unordered_map>

namespace mpm
{
  void
  NonlocalLength::declare_parameters(ParameterHandler  &prm,
                                     const std::string &averaged)
  {
    prm.declare_entry("nonlocal length",
                      "0",
                      Patterns::Anything(),
                      "l >= 0 in m: " + averaged +
                        ". The average takes the points within l (bell "
                        "weight) or 3 l (Gaussian); l should span two cells "
                        "or more. 0: local.");
    prm.declare_entry("nonlocal weight",
                      "bell",
                      Patterns::Selection("bell|Gaussian"),
                      "bell: (1 - r^2/l^2)^2 for r < l. Gaussian: "
                      "exp(-r^2 / (2 l^2)) for r < 3 l.");
  }


  void
  NonlocalLength::parse(const ParameterHandler &prm, const std::string &path)
  {
    length = Parse::bounded_double(prm, path, "nonlocal length", 0, 1e300);
    weight =
      prm.get("nonlocal weight") == "bell" ? Weight::bell : Weight::gauss;
  }


  template <int dim>
  NonlocalAverage<dim>::NonlocalAverage(const NonlocalLength &l)
    : length(l.length)
    , support(l.weight == NonlocalLength::Weight::bell ? l.length
                                                       : 3 * l.length)
    , kind(l.weight)
  {
  }


  template <int dim>
  double
  NonlocalAverage<dim>::weight(const double r2) const
  {
    if (r2 >= support * support)
      return 0.;
    const double x = r2 / (length * length);
    return kind == NonlocalLength::Weight::bell ? (1. - x) * (1. - x)
                                                : std::exp(-0.5 * x);
  }


  namespace
  {
    /// The points of other ranks within @p support of this rank's points
    /// @p x: each rank sends what lies within the support of the others'
    /// bounding boxes. Returns (x, volume, value) packed, dim + 2 each.
    template <int dim>
    std::vector<double>
    halo(const std::vector<Point<dim>> &x,
         const std::vector<double>     &volume,
         const std::vector<double>     &value,
         const double                   support,
         const MPI_Comm                 comm)
    {
      const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
      if (n_ranks == 1)
        return {};
      const unsigned int me = Utilities::MPI::this_mpi_process(comm);
      // Bounding boxes: min then max per direction; empty: min > max.
      std::vector<double> box(2 * dim);
      for (unsigned int d = 0; d < dim; ++d)
        box[d] = 1e300, box[dim + d] = -1e300;
      for (const auto &p : x)
        for (unsigned int d = 0; d < dim; ++d)
          {
            box[d]       = std::min(box[d], p[d]);
            box[dim + d] = std::max(box[dim + d], p[d]);
          }
      const auto boxes = Utilities::MPI::all_gather(comm, box);

      std::map<unsigned int, std::vector<double>> send;
      for (unsigned int r = 0; r < n_ranks; ++r)
        {
          if (r == me || boxes[r][0] > boxes[r][dim])
            continue;
          std::vector<double> &out = send[r];
          for (unsigned int i = 0; i < x.size(); ++i)
            {
              double distance2 = 0;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  const double gap = std::max(
                    {boxes[r][d] - x[i][d], x[i][d] - boxes[r][dim + d], 0.});
                  distance2 += gap * gap;
                }
              if (distance2 < support * support)
                {
                  for (unsigned int d = 0; d < dim; ++d)
                    out.push_back(x[i][d]);
                  out.push_back(volume[i]);
                  out.push_back(value[i]);
                }
            }
        }
      std::vector<double> received;
      for (const auto &[rank, data] : Utilities::MPI::some_to_some(comm, send))
        received.insert(received.end(), data.begin(), data.end());
      return received;
    }
  } // namespace


  template <int dim>
  std::vector<double>
  NonlocalAverage<dim>::average(const std::vector<Point<dim>> &x,
                                const std::vector<double>     &volume,
                                const std::vector<double>     &value,
                                const std::vector<double>     &floor,
                                const MPI_Comm                 comm) const
  {
    // All contributors: this rank's points, then the halo's.
    std::vector<Point<dim>>   y = x;
    std::vector<double>       v = volume, f = value;
    const std::vector<double> received = halo(x, volume, value, support, comm);
    for (unsigned int k = 0; k < received.size(); k += dim + 2)
      {
        Point<dim> p;
        for (unsigned int d = 0; d < dim; ++d)
          p[d] = received[k + d];
        y.push_back(p);
        v.push_back(received[k + dim]);
        f.push_back(received[k + dim + 1]);
      }

    // Bins of the support's size: a point's neighbours lie in the 3^dim
    // bins around its own.
    auto bin_of = [this](const Point<dim> &p) {
      std::array<long long, dim> b;
      for (unsigned int d = 0; d < dim; ++d)
        b[d] = static_cast<long long>(std::floor(p[d] / support));
      return b;
    };
    auto key = [](const std::array<long long, dim> &b) {
      // Bins fit in 21 bits each way for any sensible scene.
      unsigned long long k = 0;
      for (unsigned int d = 0; d < dim; ++d)
        k = (k << 21) ^ static_cast<unsigned long long>(b[d] & 0x1fffff);
      return k;
    };
    struct Bin
    {
      std::vector<unsigned int> members;
      double                    largest = -1e300;
    };
    std::unordered_map<unsigned long long, Bin> bins;
    for (unsigned int j = 0; j < y.size(); ++j)
      {
        Bin &bin = bins[key(bin_of(y[j]))];
        bin.members.push_back(j);
        bin.largest = std::max(bin.largest, f[j]);
      }

    constexpr unsigned int            n_around = Utilities::pow(3, dim);
    std::array<const Bin *, n_around> around;
    std::vector<double>               result(x.size());
    for (unsigned int i = 0; i < x.size(); ++i)
      {
        const auto home    = bin_of(x[i]);
        double     largest = -1e300;
        for (unsigned int n = 0; n < n_around; ++n)
          {
            std::array<long long, dim> b = home;
            for (unsigned int d = 0, m = n; d < dim; ++d, m /= 3)
              b[d] += static_cast<long long>(m % 3) - 1;
            const auto it = bins.find(key(b));
            around[n]     = it == bins.end() ? nullptr : &it->second;
            if (around[n] != nullptr)
              largest = std::max(largest, around[n]->largest);
          }
        if (largest <= floor[i])
          {
            result[i] = floor[i];
            continue;
          }
        double numerator = 0, denominator = 0;
        for (const Bin *bin : around)
          if (bin != nullptr)
            for (const unsigned int j : bin->members)
              {
                const double w = weight(x[i].distance_square(y[j])) * v[j];
                numerator += w * f[j];
                denominator += w;
              }
        // The point itself has weight 1: the denominator is positive.
        result[i] = numerator / denominator;
      }
    return result;
  }


  template class NonlocalAverage<1>;
  template class NonlocalAverage<2>;
  template class NonlocalAverage<3>;
} // namespace mpm
