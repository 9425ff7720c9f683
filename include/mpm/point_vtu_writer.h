#ifndef mpm_point_vtu_writer_h
#define mpm_point_vtu_writer_h

#include <deal.II/base/mpi.h>

#include <functional>
#include <string>
#include <vector>

namespace mpm
{
  /**
   * Material points as one VTK XML unstructured-grid file (.vtu) per output
   * time for all ranks: each rank's points are a piece of it, their arrays
   * compressed (zlib) and appended, each rank writing its part of every
   * array at its offset through MPI-IO. Arrays are produced, compressed
   * and written one at a time, so the writer needs one array of this
   * rank's points and nothing else: deal.II's writers first build a patch
   * per point and then copies of all the data, which set a run's peak
   * memory (measured: 400 bytes per point on top of the run's 300).
   */
  class PointVtuWriter
  {
  public:
    /// One point field: its name, the number of components written per
    /// point (vectors are written with 3, tensors with 9, as VTK expects),
    /// and a function that fills a buffer with them, point after point, in
    /// the order of every other field.
    struct Field
    {
      std::string                               name;
      unsigned int                              n_components;
      std::function<void(std::vector<float> &)> fill;
    };

    /// @p positions fills 3 coordinates per point (the points' order).
    PointVtuWriter(MPI_Comm                                  comm,
                   unsigned long long                        n_local_points,
                   std::function<void(std::vector<float> &)> positions);

    /// Write @p file (collective); @p time and @p cycle go into its field
    /// data.
    void
    write(const std::string        &file,
          const std::vector<Field> &fields,
          double                    time,
          unsigned int              cycle) const;

    /// The record (.pvtu) that names the single @p piece written with
    /// @p fields (written by the caller's root).
    static void
    write_pvtu(const std::string        &file,
               const std::string        &piece,
               const std::vector<Field> &fields);

  private:
    MPI_Comm                                  comm;
    unsigned long long                        n_local;
    unsigned long long                        n_global;
    unsigned long long                        first; ///< this rank's first
    std::function<void(std::vector<float> &)> positions;
  };
} // namespace mpm

#endif
