#ifndef mpm_checkpoint_h
#define mpm_checkpoint_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace mpm
{
  using namespace dealii;

  template <int dim>
  class BackgroundGrid;
  template <int dim>
  class MaterialPoints;

  /// When and where checkpoints are written.
  struct CheckpointParameters
  {
    static void
    declare_parameters(ParameterHandler &prm);
    /// @p output_directory is the default's parent.
    void
    parse_parameters(ParameterHandler  &prm,
                     const std::string &output_directory);

    bool
    enabled() const
    {
      return interval > 0 || wall_interval > 0;
    }

    double      interval;      ///< simulated time; 0: not by time
    double      wall_interval; ///< wall-clock seconds; 0: not by wall time
    std::string directory;
  };


  /**
   * What a run holds besides its grid and points, as named numbers
   * (written exactly, in hexadecimal floating point) and the output
   * records. Each component puts in and takes out its own entries.
   */
  struct RunState
  {
    std::map<std::string, double>               values;
    std::vector<std::pair<double, std::string>> particle_files, grid_files;
    /// Every entry of the scene that wrote the checkpoint, by its path
    /// ("Bodies/Body 0/density"), as given: a restart names what differs.
    std::map<std::string, std::string> scene;

    double
    get(const std::string &key) const;

    /// This rank's share of a sum over the ranks stored under @p key:
    /// all of it on the first rank, 0 on the others (a restart may run on
    /// another number of ranks).
    double
    share_of_rank(const std::string &key, MPI_Comm comm) const;

    void
    write(const std::string &file) const;
    static RunState
    read(const std::string &file);
  };


  /**
   * A checkpoint is a directory: the triangulation with the points attached
   * (deal.II's distributed save, which p4est can load on any number of
   * ranks) and state.txt. It is written into '<directory>.partial' and
   * swapped in by renames once complete, so a kill at any moment leaves the
   * previous checkpoint usable: in '<directory>', or, if the kill fell
   * between the two renames, in '<directory>.old', which locate() finds.
   */
  namespace Checkpoint
  {
    template <int dim>
    void
    save(const std::string   &directory,
         BackgroundGrid<dim> &grid,
         MaterialPoints<dim> &points,
         const RunState      &state,
         MPI_Comm             comm);

    /// The complete checkpoint to restart from, given the directory the
    /// user names; an InputError naming '--restart' if there is none.
    std::string
    locate(const std::string &directory);

    /// The file the triangulation is saved under in @p checkpoint.
    std::string
    grid_file(const std::string &checkpoint);
  } // namespace Checkpoint
} // namespace mpm

#endif
