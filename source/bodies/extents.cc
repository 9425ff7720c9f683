#include <mpm/bodies/extents.h>
#include <mpm/parameters.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace mpm
{
  template <int dim>
  BodyExtents<dim>::BodyExtents(const BackgroundGrid<dim> &grid,
                                const Tensor<1, dim>      &gravity,
                                const double               percentile,
                                const double               thickness,
                                const unsigned int         n_bodies,
                                MPI_Comm                   comm)
    : grid(grid)
    , percentile(percentile)
    , thickness(thickness)
    , n_bodies(n_bodies)
    , vertical(numbers::invalid_unsigned_int)
    , n_columns(1)
    , comm(comm)
  {
    unsigned int n_nonzero = 0;
    for (unsigned int d = 0; d < dim; ++d)
      if (gravity[d] != 0)
        {
          vertical = d;
          ++n_nonzero;
        }
    if (thickness > 0 && (n_nonzero != 1 || dim == 1))
      throw InputError("Output/front thickness",
                       (std::ostringstream() << thickness).str(),
                       "needs 'Simulation/gravity' along one axis of the "
                       "grid in 2D or 3D (the thickness is measured along "
                       "it); 0 for no deposit front");
    if (thickness > 0)
      for (unsigned int d = 0; d < dim; ++d)
        if (d != vertical)
          {
            horizontal.push_back(d);
            n_columns *= grid.parameters().n_cells[d];
          }
  }


  template <int dim>
  std::vector<std::string>
  BodyExtents<dim>::columns() const
  {
    std::vector<std::string> c;
    for (unsigned int b = 0; b < n_bodies; ++b)
      {
        const std::string body = "body" + std::to_string(b) + "_";
        for (const std::string kind : {"", "front_"})
          for (unsigned int d = 0; d < dim; ++d)
            for (const std::string end : {"min", "max"})
              c.push_back(body + "xyz"[d] + "_" + kind + end);
        for (const unsigned int d : horizontal)
          for (const std::string end : {"min", "max"})
            c.push_back(body + "xyz"[d] + "_deposit_" + end);
      }
    return c;
  }


  template <int dim>
  std::vector<double>
  BodyExtents<dim>::values(const MaterialPoints<dim> &points) const
  {
    const double              inf    = std::numeric_limits<double>::infinity();
    const std::vector<double> lowest = boxes(points);
    const std::vector<double> counts = histograms(points);
    const Columns             columns =
      thickness > 0 ? columns_of_cells(points) : Columns();
    const auto         &prm     = grid.parameters();
    const unsigned int  n_edges = 2 * horizontal.size();
    std::vector<double> v;
    for (unsigned int b = 0; b < n_bodies; ++b)
      {
        for (unsigned int d = 0; d < dim; ++d)
          {
            v.push_back(lowest[2 * dim * b + d]);
            v.push_back(-lowest[2 * dim * b + dim + d]);
          }
        for (unsigned int d = 0; d < dim; ++d)
          {
            // The bins' edges where p % of the points are passed, from
            // either end.
            const unsigned int n_bins = bins_per_cell * prm.n_cells[d];
            const double      *count =
              counts.data() + counts.size() / n_bodies * b + bins_before(d);
            double n = 0;
            for (unsigned int k = 0; k < n_bins; ++k)
              n += count[k];
            const double bin    = grid.cell_size()[d] / bins_per_cell;
            const double needed = std::max(1., std::ceil(percentile / 100 * n));
            double       low = inf, high = -inf, sum = 0;
            for (unsigned int k = 0; k < n_bins && n > 0; ++k)
              if ((sum += count[k]) >= needed)
                {
                  high = prm.lower_corner[d] + (k + 1) * bin;
                  break;
                }
            sum = 0;
            for (unsigned int k = n_bins; k-- > 0 && n > 0;)
              if ((sum += count[k]) >= needed)
                {
                  low = prm.lower_corner[d] + k * bin;
                  break;
                }
            v.push_back(low);
            v.push_back(high);
          }
        if (thickness > 0)
          {
            // The columns at least T thick, or else the thickest.
            const double *thick = columns.thickness.data() + n_columns * b;
            const double *edge = columns.edges.data() + n_edges * n_columns * b;
            const double  enough =
              std::min(thickness, *std::max_element(thick, thick + n_columns));
            for (unsigned int a = 0; a < horizontal.size(); ++a)
              {
                double low = inf, high = -inf;
                for (unsigned int k = 0; k < n_columns; ++k)
                  if (thick[k] > 0 && thick[k] >= enough)
                    {
                      low  = std::min(low, edge[n_edges * k + 2 * a]);
                      high = std::max(high, -edge[n_edges * k + 2 * a + 1]);
                    }
                v.push_back(low);
                v.push_back(high);
              }
          }
      }
    return v;
  }


  template <int dim>
  std::vector<double>
  BodyExtents<dim>::boxes(const MaterialPoints<dim> &points) const
  {
    const double        inf = std::numeric_limits<double>::infinity();
    std::vector<double> lowest(2 * dim * n_bodies, inf);
    const unsigned int  body = points.layout().body;
    for (const auto &p : points.handler())
      {
        const unsigned int b = p.get_properties()[body];
        double            *l = lowest.data() + 2 * dim * b;
        const Point<dim>  &x = p.get_location();
        for (unsigned int d = 0; d < dim; ++d)
          {
            l[d]       = std::min(l[d], x[d]);
            l[dim + d] = std::min(l[dim + d], -x[d]);
          }
      }
    MPI_Allreduce(
      MPI_IN_PLACE, lowest.data(), lowest.size(), MPI_DOUBLE, MPI_MIN, comm);
    return lowest;
  }


  template <int dim>
  unsigned int
  BodyExtents<dim>::bins_before(const unsigned int axis) const
  {
    unsigned int n = 0;
    for (unsigned int d = 0; d < axis; ++d)
      n += bins_per_cell * grid.parameters().n_cells[d];
    return n;
  }


  template <int dim>
  std::vector<double>
  BodyExtents<dim>::histograms(const MaterialPoints<dim> &points) const
  {
    const auto               &prm = grid.parameters();
    std::vector<unsigned int> offset(dim + 1, 0);
    for (unsigned int d = 0; d <= dim; ++d)
      offset[d] = bins_before(d);
    std::vector<double> counts(n_bodies * offset[dim], 0.);
    const unsigned int  body = points.layout().body;
    for (const auto &p : points.handler())
      {
        const unsigned int b = p.get_properties()[body];
        const Point<dim>  &x = p.get_location();
        for (unsigned int d = 0; d < dim; ++d)
          {
            const unsigned int n_bins = offset[d + 1] - offset[d];
            const double       s      = (x[d] - prm.lower_corner[d]) *
                             grid.inverse_cell_size()[d] * bins_per_cell;
            const unsigned int k =
              std::min<double>(std::max(s, 0.), n_bins - 1);
            counts[b * offset[dim] + offset[d] + k] += 1;
          }
      }
    MPI_Allreduce(
      MPI_IN_PLACE, counts.data(), counts.size(), MPI_DOUBLE, MPI_SUM, comm);
    return counts;
  }


  template <int dim>
  unsigned int
  BodyExtents<dim>::column_of(const Point<dim> &x) const
  {
    const auto  &prm   = grid.parameters();
    unsigned int index = 0;
    for (const unsigned int d : horizontal)
      {
        const double s =
          (x[d] - prm.lower_corner[d]) * grid.inverse_cell_size()[d];
        const unsigned int c =
          std::min<double>(std::max(s, 0.), prm.n_cells[d] - 1);
        index = index * prm.n_cells[d] + c;
      }
    return index;
  }


  template <int dim>
  typename BodyExtents<dim>::Columns
  BodyExtents<dim>::columns_of_cells(const MaterialPoints<dim> &points) const
  {
    const unsigned int n_edges = 2 * horizontal.size();
    Columns            c;
    c.thickness.assign(n_columns * n_bodies, 0.);
    c.edges.assign(n_edges * n_columns * n_bodies,
                   std::numeric_limits<double>::infinity());
    const FieldLayout &l = points.layout();
    for (const auto &p : points.handler())
      {
        const double      *q = p.get_properties().data();
        const Point<dim>  &x = p.get_location();
        const double       r = 0.5 * std::pow(q[l.volume], 1. / dim);
        const unsigned int k =
          n_columns * static_cast<unsigned int>(q[l.body]) + column_of(x);
        c.thickness[k] += l.opening == FieldLayout::absent
                            ? q[l.volume]
                            : q[l.volume] * std::exp(-q[l.opening]);
        double *edge = c.edges.data() + n_edges * k;
        for (unsigned int a = 0; a < horizontal.size(); ++a)
          {
            edge[2 * a] = std::min(edge[2 * a], x[horizontal[a]] - r);
            edge[2 * a + 1] =
              std::min(edge[2 * a + 1], -(x[horizontal[a]] + r));
          }
      }
    MPI_Allreduce(MPI_IN_PLACE,
                  c.thickness.data(),
                  c.thickness.size(),
                  MPI_DOUBLE,
                  MPI_SUM,
                  comm);
    MPI_Allreduce(
      MPI_IN_PLACE, c.edges.data(), c.edges.size(), MPI_DOUBLE, MPI_MIN, comm);
    // The volume over the column's cross-section, the cells' width across
    // gravity (their area in 3D).
    double cross_section = 1;
    for (const unsigned int d : horizontal)
      cross_section *= grid.cell_size()[d];
    for (double &t : c.thickness)
      t /= cross_section;
    return c;
  }


  template class BodyExtents<1>;
  template class BodyExtents<2>;
  template class BodyExtents<3>;
} // namespace mpm
