// Which symmetric 3x3 eigen-decomposition should the log-strain materials
// use? For each solver: the error of eps = 1/2 ln(b) rebuilt from the
// decomposition, for stretches well apart and for two (and three) nearly
// equal, and the cost per decomposition. Prints CSV.
//
//   build/benchmarks/eigensolver/eigensolver > eigensolver.csv
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/timer.h>

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <functional>
#include <iostream>
#include <random>

using namespace dealii;

using Pairs = std::array<std::pair<double, Tensor<1, 3>>, 3>;

namespace
{
  Pairs
  with_eigen(const SymmetricTensor<2, 3> &b, const bool direct)
  {
    Eigen::Matrix3d m;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        m(i, j) = b[i][j];
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> s;
    if (direct)
      s.computeDirect(m);
    else
      s.compute(m);
    Pairs p;
    for (unsigned int k = 0; k < 3; ++k)
      {
        p[k].first = s.eigenvalues()(k);
        for (unsigned int i = 0; i < 3; ++i)
          p[k].second[i] = s.eigenvectors()(i, k);
      }
    return p;
  }

  Pairs
  with_dealii(const SymmetricTensor<2, 3>             &b,
              const SymmetricTensorEigenvectorMethod method)
  {
    return eigenvectors(b, method);
  }

  /// 1/2 ln(b) rebuilt from a decomposition.
  SymmetricTensor<2, 3>
  half_log(const Pairs &p)
  {
    SymmetricTensor<2, 3> e;
    for (const auto &[value, vector] : p)
      e += (0.5 * std::log(value)) * symmetrize(outer_product(vector, vector));
    return e;
  }

  Tensor<2, 3>
  random_rotation(std::mt19937 &rng)
  {
    std::normal_distribution<double> n;
    Tensor<1, 3>                     a({n(rng), n(rng), n(rng)});
    a /= a.norm();
    const double angle = 3.0 * std::uniform_real_distribution<double>()(rng);
    Tensor<2, 3> K;
    K[0][1] = -a[2], K[0][2] = a[1], K[1][2] = -a[0];
    K[1][0] = a[2], K[2][0] = -a[1], K[2][1] = a[0];
    Tensor<2, 3> R = unit_symmetric_tensor<3>();
    R += std::sin(angle) * K + (1 - std::cos(angle)) * (K * K);
    return R;
  }
} // namespace

int
main()
{
  using Solver = std::function<Pairs(const SymmetricTensor<2, 3> &)>;
  const std::vector<std::pair<std::string, Solver>> solvers = {
    {"dealii_hybrid",
     [](const auto &b) {
       return with_dealii(b, SymmetricTensorEigenvectorMethod::hybrid);
     }},
    {"dealii_ql",
     [](const auto &b) {
       return with_dealii(b,
                          SymmetricTensorEigenvectorMethod::ql_implicit_shifts);
     }},
    {"dealii_jacobi",
     [](const auto &b) {
       return with_dealii(b, SymmetricTensorEigenvectorMethod::jacobi);
     }},
    {"eigen_iterative", [](const auto &b) { return with_eigen(b, false); }},
    {"eigen_direct", [](const auto &b) { return with_eigen(b, true); }}};

  // Log strains: well apart, two or three within a gap, two equal.
  const std::vector<std::pair<std::string, std::array<double, 3>>> cases = {
    {"distinct", {0.1, -0.05, 0.02}},
    {"two_within_1e-3", {0.1, 0.1 + 1e-3, -0.05}},
    {"two_within_1e-5", {0.1, 0.1 + 1e-5, -0.05}},
    {"two_within_1e-8", {0.1, 0.1 + 1e-8, -0.05}},
    {"two_equal", {0.1, 0.1, -0.05}},
    {"three_within_1e-5", {0.02, 0.02 + 1e-5, 0.02 - 1e-5}},
    {"three_within_1e-8", {0.02, 0.02 + 1e-8, 0.02 - 1e-8}}};

  const unsigned int n = 200000;
  std::cout << "solver,case,max_error_in_eps,ns_per_decomposition\n";
  for (const auto &[name, solve] : solvers)
    for (const auto &[label, eps] : cases)
      {
        std::mt19937                       rng(1);
        std::vector<SymmetricTensor<2, 3>> b(n), exact(n);
        for (unsigned int k = 0; k < n; ++k)
          {
            const Tensor<2, 3>    R = random_rotation(rng);
            SymmetricTensor<2, 3> d, e;
            for (unsigned int i = 0; i < 3; ++i)
              d[i][i] = std::exp(2 * eps[i]), e[i][i] = eps[i];
            b[k]     = symmetrize(Tensor<2, 3>(R * Tensor<2, 3>(d) * transpose(R)));
            exact[k] = symmetrize(Tensor<2, 3>(R * Tensor<2, 3>(e) * transpose(R)));
          }
        double error = 0, checksum = 0;
        Timer  timer;
        for (unsigned int k = 0; k < n; ++k)
          checksum += solve(b[k])[0].first;
        timer.stop();
        for (unsigned int k = 0; k < n; k += 10)
          error = std::max(error, (half_log(solve(b[k])) - exact[k]).norm());
        std::cout << name << "," << label << "," << error << ","
                  << 1e9 * timer.wall_time() / n << (checksum == 0 ? " " : "")
                  << "\n";
      }
}
