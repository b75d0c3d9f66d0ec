// TripletAssembly against Eigen's setFromTriplets: bitwise the same matrices, whether the pattern
// is reused (the same (row, col) sequence with new values, or another sequence over the same
// entries) or rebuilt (a changed structure).
#include <catch2/catch.hpp>
#include <algorithm>
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
  // A different sequence over the same entries (reordered; one entry's triplet repeated) is
  // scattered into the stored pattern, and is still exact.
  std::shuffle(t.begin(), t.end(), rng);
  assembly.Assemble(t, n, &out);
  CHECK(BitwiseEqual(out, Reference(t, n)));
  t.push_back(Eigen::Triplet<double>(t[17].row(), t[17].col(), value(rng)));
  assembly.Assemble(t, n, &out);
  CHECK(BitwiseEqual(out, Reference(t, n)));
  CHECK(assembly.rebuilt() == 1);
  CHECK(assembly.reused() == 5);
  // A new entry is rebuilt, and is still exact.
  auto present = [&](int r, int c) {
    for (const auto& e : t)
      if (e.row() == r && e.col() == c) return true;
    return false;
  };
  int r = 0, c = 0;
  while (present(r, c)) c == n - 1 ? (++r, c = 0) : ++c;
  t.emplace_back(r, c, value(rng));
  assembly.Assemble(t, n, &out);
  CHECK(BitwiseEqual(out, Reference(t, n)));
  CHECK(assembly.rebuilt() == 2);
  // An entry none of whose triplets is left: rebuilt (setFromTriplets leaves the entry out).
  const int dropRow = t[0].row(), dropCol = t[0].col();
  t.erase(std::remove_if(t.begin(), t.end(),
                         [&](const Eigen::Triplet<double>& e) {
                           return e.row() == dropRow && e.col() == dropCol;
                         }),
          t.end());
  assembly.Assemble(t, n, &out);
  CHECK(BitwiseEqual(out, Reference(t, n)));
  CHECK(assembly.rebuilt() == 3);
  // A different size with the same triplets is rebuilt.
  assembly.Assemble(t, n + 2, &out);
  CHECK(BitwiseEqual(out, Reference(t, n + 2)));
  CHECK(assembly.rebuilt() == 4);
}
