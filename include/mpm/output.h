#ifndef mpm_output_h
#define mpm_output_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/data_out_base.h>
#include <deal.II/base/parameter_handler.h>

#include <mpm/background_grid.h>
#include <mpm/material_points.h>
#include <mpm/statistics.h>

#include <fstream>
#include <functional>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  struct RunState;
  template <int dim>
  class TimeIntegrator;

  struct OutputParameters
  {
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    /// True if field @p name (velocity, displacement, ...) is written.
    bool
    writes(const std::string &name) const;

    std::string              directory;
    double                   interval; ///< simulated time; 0 = every step
    std::vector<std::string> fields;
    bool                     grid_output;
    /// Particles as HDF5 + XDMF (one .h5 per output time, written by all
    /// ranks through MPI-IO) instead of VTU.
    bool hdf5;
    /// Columns with where each body reaches (runout, length; see
    /// BodyExtents): the box around its points, the front of
    /// front_percentile % of them, and with front_thickness > 0 the edges
    /// of the deposit at least that thick.
    bool   body_extents;
    double front_percentile;
    double front_thickness;
    double progress_interval; ///< wall seconds
    /// Remove an earlier run's output from the directory (else refuse).
    bool replace_existing;
  };


  /**
   * A point field as the particle files hold it: its name in the files,
   * its values per point and how they read (scalar, vector or tensor), and
   * how they are computed from a point. The fields 'Output/fields' can ask
   * for are one table in output.cc.
   */
  template <int dim>
  struct PointField
  {
    std::string                                              name;
    unsigned int                                             n_values;
    DataComponentInterpretation::DataComponentInterpretation kind;
    std::function<
      void(const typename Particles::ParticleHandler<dim>::particle_iterator &,
           double *)>
      values;
  };


  /**
   * Everything written to disk: particles as VTU (+PVTU, PVD), optionally
   * the grid, and statistics.csv. A file is only written from a state that
   * passed the integrator's checks, so after a failed run the files on
   * disk are the last good ones.
   */
  template <int dim>
  class Output
  {
  public:
    Output(const OutputParameters         &parameters,
           const BackgroundGrid<dim>      &grid,
           const MaterialPoints<dim>      &points,
           const TimeIntegrator<dim>      &integrator,
           const Tensor<1, dim>           &gravity,
           const std::vector<std::string> &extra_columns,
           MPI_Comm                        comm,
           const RunState                 *resume = nullptr);

    /// The frame counter and the .pvd records, for a checkpoint (a restart
    /// passes them back to the constructor).
    void
    save_state(RunState &state) const;

    /// Write statistics and, if due, the fields; @p extra are values of
    /// the extra columns (verification errors).
    void
    write(const Statistics<dim>     &statistics,
          const std::vector<double> &extra,
          const double               wall_seconds);

    /// Is an output due at time @p t? And the next time one is due.
    double
    next_output_time() const
    {
      return next_time;
    }

  private:
    /// The first output time after time @p t.
    double
    output_time_after(const double t) const;

    using PointField = mpm::PointField<dim>;
    /// The fields 'Output/fields' asks for, in the order of the files.
    std::vector<PointField>
    point_fields() const;
    void
    write_particles();
    void
    write_vtu_particles(const std::vector<PointField> &fields);
    void
    write_hdf5_particles(const std::vector<PointField> &fields);
    void
    write_grid();
    /// VTU (+PVTU) of @p out at this time, and the PVD record @p base.pvd.
    template <int patch_dim>
    void
    write_files(DataOutInterface<patch_dim, dim>            &out,
                const std::string                           &base,
                std::vector<std::pair<double, std::string>> &records);
    /// The HDF5 file of @p out at this time with its XDMF description, and
    /// the XDMF collection @p base.xdmf of all times.
    void
    write_hdf5_files(DataOutInterface<0, dim> &out,
                     const std::size_t         n_local_points,
                     const std::string        &base,
                     std::vector<std::pair<double, std::string>> &records);
    /// Move the files of @p name (the partial directory's, @p name last)
    /// into the output directory (root only).
    void
    publish_frame(const std::string &name) const;

    const OutputParameters                      prm;
    const BackgroundGrid<dim>                  &grid;
    const MaterialPoints<dim>                  &points;
    const TimeIntegrator<dim>                  &integrator;
    const Tensor<1, dim>                        gravity;
    MPI_Comm                                    comm;
    const bool                                  is_root;
    unsigned int                                counter   = 0;
    double                                      next_time = 0;
    std::ofstream                               statistics_file;
    std::vector<std::pair<double, std::string>> particle_files, grid_files;
  };
} // namespace mpm

#endif
