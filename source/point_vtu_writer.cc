#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <mpm/point_vtu_writer.h>

#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

namespace mpm
{
  using namespace dealii;

  namespace
  {
    /// One data array of the appended section: its XML element (less the
    /// offset), and how this rank's part is made.
    struct Array
    {
      std::string                              element;
      std::function<void(std::vector<char> &)> fill;
    };


    /// Write @p n bytes at @p offset, in pieces that fit MPI's int count.
    void
    write_at(MPI_File file, MPI_Offset offset, const char *data, std::size_t n)
    {
      constexpr std::size_t largest = 1u << 30;
      while (n > 0)
        {
          const std::size_t piece = std::min(n, largest);
          const int         error = MPI_File_write_at(file,
                                              offset,
                                              data,
                                              static_cast<int>(piece),
                                              MPI_BYTE,
                                              MPI_STATUS_IGNORE);
          AssertThrowMPI(error);
          offset += piece;
          data += piece;
          n -= piece;
        }
    }


    template <typename T>
    void
    as_bytes(const std::vector<T> &values, std::vector<char> &bytes)
    {
      bytes.resize(values.size() * sizeof(T));
      std::copy_n(reinterpret_cast<const char *>(values.data()),
                  bytes.size(),
                  bytes.data());
    }
  } // namespace


  PointVtuWriter::PointVtuWriter(
    MPI_Comm                                  comm,
    const unsigned long long                  n_local_points,
    std::function<void(std::vector<float> &)> positions)
    : comm(comm)
    , n_local(n_local_points)
    , positions(std::move(positions))
  {
  }


  namespace
  {
    /// @p bytes as VTK's zlib-compressed binary data: the header (UInt64:
    /// number of blocks, block size, size of the last block, compressed
    /// size of each block) and the blocks, each compressed on its own.
    std::vector<char>
    compress(const std::vector<char> &bytes)
    {
      constexpr std::uint64_t    block    = 1u << 20;
      const std::uint64_t        n        = bytes.size();
      const std::uint64_t        n_blocks = (n + block - 1) / block;
      std::vector<std::uint64_t> header   = {
          n_blocks, block, n_blocks == 0 ? 0 : n - (n_blocks - 1) * block};
      std::vector<char> data;
      for (std::uint64_t k = 0; k < n_blocks; ++k)
        {
          const std::uint64_t size = std::min(block, n - k * block);
          uLongf              out  = compressBound(size);
          const std::size_t   at   = data.size();
          data.resize(at + out);
          const int error =
            compress2(reinterpret_cast<Bytef *>(data.data() + at),
                      &out,
                      reinterpret_cast<const Bytef *>(bytes.data() + k * block),
                      size,
                      Z_BEST_SPEED);
          AssertThrow(error == Z_OK, ExcMessage("zlib failed"));
          data.resize(at + out);
          header.push_back(out);
        }
      std::vector<char> result(8 * header.size());
      std::copy_n(reinterpret_cast<const char *>(header.data()),
                  result.size(),
                  result.data());
      result.insert(result.end(), data.begin(), data.end());
      return result;
    }


    /// A number in a fixed width, so that every rank knows the length of
    /// the header before the sizes it will hold are known.
    std::string
    fixed(const unsigned long long value)
    {
      std::ostringstream s;
      s << std::setw(20) << std::setfill('0') << value;
      return s.str();
    }
  } // namespace


  /**
   * Each rank's points are one <Piece> of the file (VTK readers join the
   * pieces of a file), with its arrays compressed by zlib as VTK does
   * (blocks of 1 MiB, best speed). The appended data hold the arrays one
   * after the other, each with the parts of rank 0, 1, ...: an array's
   * place follows from a sum over the ranks, so every rank writes as soon
   * as it has compressed an array, and only the root needs the offsets of
   * all pieces, for the header, which has a fixed length.
   */
  void
  PointVtuWriter::write(const std::string        &file_name,
                        const std::vector<Field> &fields,
                        const double              time,
                        const unsigned int        cycle) const
  {
    // Points are VTK_VERTEX cells: cell i of a piece is its point i.
    std::vector<Array> arrays;
    arrays.push_back({"<DataArray type=\"Float32\" NumberOfComponents=\"3\"",
                      [&](std::vector<char> &bytes) {
                        std::vector<float> x;
                        positions(x);
                        as_bytes(x, bytes);
                      }});
    arrays.push_back({"<DataArray type=\"Int64\" Name=\"connectivity\"",
                      [&](std::vector<char> &bytes) {
                        std::vector<std::int64_t> v(n_local);
                        for (unsigned long long i = 0; i < n_local; ++i)
                          v[i] = i;
                        as_bytes(v, bytes);
                      }});
    arrays.push_back({"<DataArray type=\"Int64\" Name=\"offsets\"",
                      [&](std::vector<char> &bytes) {
                        std::vector<std::int64_t> v(n_local);
                        for (unsigned long long i = 0; i < n_local; ++i)
                          v[i] = i + 1;
                        as_bytes(v, bytes);
                      }});
    arrays.push_back({"<DataArray type=\"UInt8\" Name=\"types\"",
                      [&](std::vector<char> &bytes) {
                        bytes.assign(n_local, 1); // VTK_VERTEX
                      }});
    for (const Field &f : fields)
      arrays.push_back({"<DataArray type=\"Float32\" Name=\"" + f.name +
                          "\" NumberOfComponents=\"" +
                          std::to_string(f.n_components) + "\"",
                        [&](std::vector<char> &bytes) {
                          std::vector<float> v;
                          f.fill(v);
                          AssertDimension(v.size(), n_local * f.n_components);
                          as_bytes(v, bytes);
                        }});

    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
    const unsigned int rank    = Utilities::MPI::this_mpi_process(comm);
    // The header, with the piece of rank r holding n_points[r] points and
    // array a at offsets[r][a]; its length does not depend on them.
    const auto header = [&](const std::vector<unsigned long long> &n_points,
                            const std::vector<unsigned long long> &offsets) {
      std::ostringstream h;
      h << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
           "byte_order=\"LittleEndian\" header_type=\"UInt64\" "
           "compressor=\"vtkZLibDataCompressor\">\n"
        << "  <UnstructuredGrid>\n"
        << "    <FieldData>\n"
        << "      <DataArray type=\"Float64\" Name=\"TIME\" "
           "NumberOfTuples=\"1\" format=\"ascii\">"
        << std::setprecision(17) << std::scientific << time << "</DataArray>\n"
        << "      <DataArray type=\"Int32\" Name=\"CYCLE\" "
           "NumberOfTuples=\"1\" format=\"ascii\">"
        << fixed(cycle) << "</DataArray>\n"
        << "    </FieldData>\n";
      for (unsigned int r = 0; r < n_ranks; ++r)
        {
          const auto element = [&](const unsigned int a) {
            h << "      " << arrays[a].element
              << " format=\"appended\" offset=\""
              << fixed(offsets[r * arrays.size() + a]) << "\"/>\n";
          };
          h << "    <Piece NumberOfPoints=\"" << fixed(n_points[r])
            << "\" NumberOfCells=\"" << fixed(n_points[r]) << "\">\n"
            << "    <Points>\n";
          element(0);
          h << "    </Points>\n    <Cells>\n";
          for (unsigned int a = 1; a < 4; ++a)
            element(a);
          h << "    </Cells>\n    <PointData>\n";
          for (unsigned int a = 4; a < arrays.size(); ++a)
            element(a);
          h << "    </PointData>\n    </Piece>\n";
        }
      h << "  </UnstructuredGrid>\n"
        << "  <AppendedData encoding=\"raw\">\n_";
      return h.str();
    };
    const std::vector<unsigned long long> zeros(n_ranks * arrays.size(), 0);
    const MPI_Offset                      start =
      header(std::vector<unsigned long long>(n_ranks, 0), zeros).size();

    MPI_File file;
    int      error = MPI_File_open(comm,
                              file_name.c_str(),
                              MPI_MODE_CREATE | MPI_MODE_WRONLY,
                              MPI_INFO_NULL,
                              &file);
    AssertThrowMPI(error);
    error = MPI_File_set_size(file, 0); // an older file of the name
    AssertThrowMPI(error);
    std::vector<char>               bytes;
    std::vector<unsigned long long> my_offsets(arrays.size());
    unsigned long long              end = 0; // of the arrays so far
    for (unsigned int a = 0; a < arrays.size(); ++a)
      {
        arrays[a].fill(bytes);
        const std::vector<char>  data   = compress(bytes);
        const unsigned long long size   = data.size();
        unsigned long long       before = 0;
        error =
          MPI_Exscan(&size, &before, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, comm);
        AssertThrowMPI(error);
        if (rank == 0)
          before = 0; // MPI_Exscan leaves rank 0's result undefined
        my_offsets[a] = end + before;
        write_at(file, start + my_offsets[a], data.data(), data.size());
        end += Utilities::MPI::sum(size, comm);
      }
    const std::vector<unsigned long long> n_points =
      Utilities::MPI::gather(comm, n_local, 0);
    const auto offsets_of_ranks = Utilities::MPI::gather(comm, my_offsets, 0);
    if (rank == 0)
      {
        std::vector<unsigned long long> offsets;
        for (const auto &o : offsets_of_ranks)
          offsets.insert(offsets.end(), o.begin(), o.end());
        const std::string head = header(n_points, offsets);
        Assert(head.size() == static_cast<std::size_t>(start),
               ExcInternalError());
        const std::string tail = "\n  </AppendedData>\n</VTKFile>\n";
        write_at(file, 0, head.data(), head.size());
        write_at(file, start + end, tail.data(), tail.size());
      }
    error = MPI_File_close(&file);
    AssertThrowMPI(error);
  }


  void
  PointVtuWriter::write_pvtu(const std::string        &file,
                             const std::string        &piece,
                             const std::vector<Field> &fields)
  {
    std::ofstream out(file);
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" "
           "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
        << "  <PUnstructuredGrid GhostLevel=\"0\">\n"
        << "    <PPointData>\n";
    for (const Field &f : fields)
      out << "      <PDataArray type=\"Float32\" Name=\"" << f.name
          << "\" NumberOfComponents=\"" << f.n_components << "\"/>\n";
    out << "    </PPointData>\n"
        << "    <PPoints>\n"
        << "      <PDataArray type=\"Float32\" NumberOfComponents=\"3\"/>\n"
        << "    </PPoints>\n"
        << "    <Piece Source=\"" << piece << "\"/>\n"
        << "  </PUnstructuredGrid>\n"
        << "</VTKFile>\n";
  }
} // namespace mpm
