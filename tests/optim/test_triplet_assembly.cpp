// TripletAssembly against Eigen's setFromTriplets: bitwise the same matrices, whether the pattern
// is reused (same (row, col) sequence, new values) or rebuilt (a changed sequence).
#include <catch2/catch.hpp>
#include <cstring>
#include <random>

#include "optim/triplet_assembly.h"

using namespace superdex;

namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

bool BitwiseEqual(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols() || a.nonZeros() != b.nonZeros()) return false;
  const auto nnz = static_cast<size_t>(a.nonZeros());
  return std::memcmp(a.outerIndexPtr(), b.outerIndexPtr(), sizeof(int) * (a.cols() + 1)) == 0 &&
         std::memcmp(a.innerIndexPtr(), b.innerIndexPtr(), sizeof(int) * nnz) == 0 &&
         std::memcmp(a.valuePtr(), b.valuePtr(), sizeof(double) * nnz) == 0;
}

Eigen::SparseMatrix<double> Reference(const Triplets& t, int n) {
  Eigen::SparseMatrix<double> m(n, n);
  m.setFromTriplets(t.begin(), t.end());
  m.makeCompressed();
  return m;
}

}  // namespace

TEST_CASE("triplet assembly: reused and rebuilt patterns equal setFromTriplets bitwise",
          "[optim]") {
  std::mt19937 rng(9);
  std::uniform_int_distribution<int> index(0, 29);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  const int n = 30;
  Triplets t;
  for (int k = 0; k < 400; ++k) t.emplace_back(index(rng), index(rng), value(rng));  // duplicates
  TripletAssembly assembly;
  Eigen::SparseMatrix<double> out;
  assembly.Assemble(t, n, &out);
  CHECK(BitwiseEqual(out, Reference(t, n)));
  for (int round = 0; round < 3; ++round) {
    for (auto& e : t) e = Eigen::Triplet<double>(e.row(), e.col(), 1e3 * value(rng));
    assembly.Assemble(t, n, &out);
    CHECK(BitwiseEqual(out, Reference(t, n)));
  }
  CHECK(assembly.rebuilt() == 1);
  CHECK(assembly.reused() == 3);
  // A changed sequence (one more entry, then one moved) is rebuilt, and is still exact.
  t.emplace_back(3, 7, value(rng));
  assembly.Assemble(t, n, &out);
  CHECK(BitwiseEqual(out, Reference(t, n)));
  t[5] = Eigen::Triplet<double>(t[5].row(), (t[5].col() + 1) % n, t[5].value());
  assembly.Assemble(t, n, &out);
  CHECK(BitwiseEqual(out, Reference(t, n)));
  CHECK(assembly.rebuilt() == 3);
  // A different size with the same triplets is rebuilt.
  assembly.Assemble(t, n + 2, &out);
  CHECK(BitwiseEqual(out, Reference(t, n + 2)));
  CHECK(assembly.rebuilt() == 4);
}
