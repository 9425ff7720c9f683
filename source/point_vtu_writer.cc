#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <mpm/point_vtu_writer.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <limits>
#include <sstream>

namespace mpm
{
  using namespace dealii;

  namespace
  {
    /// One data array of the appended section: its XML element (less the
    /// offset), the bytes each point adds to it, and how this rank's part
    /// is made.
    struct Array
    {
      std::string                              element;
      unsigned int                             bytes_per_point;
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
    , n_global(Utilities::MPI::sum(n_local_points, comm))
    , first(0)
    , positions(std::move(positions))
  {
    const int error =
      MPI_Exscan(&n_local, &first, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, comm);
    AssertThrowMPI(error);
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      first = 0; // MPI_Exscan leaves rank 0's result undefined
  }


  void
  PointVtuWriter::write(const std::string        &file_name,
                        const std::vector<Field> &fields,
                        const double              time,
                        const unsigned int        cycle) const
  {
    // Points are VTK_VERTEX cells: cell i is point i (global numbering).
    std::vector<Array> arrays;
    arrays.push_back({"<DataArray type=\"Float32\" NumberOfComponents=\"3\"",
                      12,
                      [&](std::vector<char> &bytes) {
                        std::vector<float> x;
                        positions(x);
                        as_bytes(x, bytes);
                      }});
    arrays.push_back({"<DataArray type=\"Int64\" Name=\"connectivity\"",
                      8,
                      [&](std::vector<char> &bytes) {
                        std::vector<std::int64_t> v(n_local);
                        for (unsigned long long i = 0; i < n_local; ++i)
                          v[i] = first + i;
                        as_bytes(v, bytes);
                      }});
    arrays.push_back({"<DataArray type=\"Int64\" Name=\"offsets\"",
                      8,
                      [&](std::vector<char> &bytes) {
                        std::vector<std::int64_t> v(n_local);
                        for (unsigned long long i = 0; i < n_local; ++i)
                          v[i] = first + i + 1;
                        as_bytes(v, bytes);
                      }});
    arrays.push_back({"<DataArray type=\"UInt8\" Name=\"types\"",
                      1,
                      [&](std::vector<char> &bytes) {
                        bytes.assign(n_local, 1); // VTK_VERTEX
                      }});
    for (const Field &f : fields)
      arrays.push_back({"<DataArray type=\"Float32\" Name=\"" + f.name +
                          "\" NumberOfComponents=\"" +
                          std::to_string(f.n_components) + "\"",
                        4 * f.n_components,
                        [&](std::vector<char> &bytes) {
                          std::vector<float> v;
                          f.fill(v);
                          AssertDimension(v.size(), n_local * f.n_components);
                          as_bytes(v, bytes);
                        }});

    // Each array of the appended section: its byte count (UInt64), then
    // the values of rank 0's points, rank 1's, ...
    std::vector<unsigned long long> offset(arrays.size() + 1, 0);
    for (unsigned int a = 0; a < arrays.size(); ++a)
      offset[a + 1] = offset[a] + 8 + n_global * arrays[a].bytes_per_point;
    std::ostringstream header;
    const auto         element = [&](const unsigned int a) {
      header << "      " << arrays[a].element
             << " format=\"appended\" offset=\"" << offset[a] << "\"/>\n";
    };
    header << "<?xml version=\"1.0\"?>\n"
           << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
              "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
           << "  <UnstructuredGrid>\n"
           << "    <FieldData>\n"
           << "      <DataArray type=\"Float64\" Name=\"TIME\" "
              "NumberOfTuples=\"1\" format=\"ascii\">"
           << std::setprecision(17) << time << "</DataArray>\n"
           << "      <DataArray type=\"Int32\" Name=\"CYCLE\" "
              "NumberOfTuples=\"1\" format=\"ascii\">"
           << cycle << "</DataArray>\n"
           << "    </FieldData>\n"
           << "    <Piece NumberOfPoints=\"" << n_global
           << "\" NumberOfCells=\"" << n_global << "\">\n"
           << "    <Points>\n";
    element(0);
    header << "    </Points>\n    <Cells>\n";
    for (unsigned int a = 1; a < 4; ++a)
      element(a);
    header << "    </Cells>\n    <PointData>\n";
    for (unsigned int a = 4; a < arrays.size(); ++a)
      element(a);
    header << "    </PointData>\n    </Piece>\n  </UnstructuredGrid>\n"
           << "  <AppendedData encoding=\"raw\">\n_";
    const std::string head = header.str();
    const std::string tail = "\n  </AppendedData>\n</VTKFile>\n";
    const bool        root = Utilities::MPI::this_mpi_process(comm) == 0;

    MPI_File file;
    int      error = MPI_File_open(comm,
                              file_name.c_str(),
                              MPI_MODE_CREATE | MPI_MODE_WRONLY,
                              MPI_INFO_NULL,
                              &file);
    AssertThrowMPI(error);
    error = MPI_File_set_size(file, 0); // an older file of the name
    AssertThrowMPI(error);
    const MPI_Offset  start = head.size();
    std::vector<char> bytes;
    for (unsigned int a = 0; a < arrays.size(); ++a)
      {
        if (root)
          {
            const std::uint64_t n = n_global * arrays[a].bytes_per_point;
            write_at(file,
                     start + offset[a],
                     reinterpret_cast<const char *>(&n),
                     8);
          }
        arrays[a].fill(bytes);
        write_at(file,
                 start + offset[a] + 8 + first * arrays[a].bytes_per_point,
                 bytes.data(),
                 bytes.size());
      }
    if (root)
      {
        write_at(file, 0, head.data(), head.size());
        write_at(file, start + offset.back(), tail.data(), tail.size());
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
