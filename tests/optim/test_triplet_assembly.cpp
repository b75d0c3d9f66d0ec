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

/// `count` triplets at random entries of an n × n matrix (duplicates among them), values in ±1.
Triplets RandomTriplets(int n, int count, std::mt19937* rng) {
  std::uniform_int_distribution<int> index(0, n - 1);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Triplets t;
  for (int k = 0; k < count; ++k) {
    const int row = index(*rng), col = index(*rng);
    t.emplace_back(row, col, value(*rng));
  }
  return t;
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
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  const int n = 30;
  Triplets t = RandomTriplets(n, 400, &rng);
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
  // A sequence that differs from the stored one only in its last triplet, moved onto another
  // stored entry: the checked scatter has written every value before it finds the difference,
  // and the path that takes over must still give setFromTriplets' values.
  {
    Triplets moved = t;
    const Eigen::Triplet<double> last = moved.back();
    moved.back() = Eigen::Triplet<double>(t[0].row(), t[0].col(), last.value());
    for (auto& e : moved) e = Eigen::Triplet<double>(e.row(), e.col(), 1e3 * value(rng));
    TripletAssembly copy = assembly;  // the same stored sequence and slots
    copy.Assemble(moved, n, &out);
    CHECK(BitwiseEqual(out, Reference(moved, n)));
    copy.Assemble(t, n, &out);  // and back: the original sequence's values
    CHECK(BitwiseEqual(out, Reference(t, n)));
  }
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

TEST_CASE("triplet assembly: 6 x 6 blocks count as their triplets at their place in the sequence",
          "[optim]") {
  // Blocks on a 6-dof grid (a rigid body's dofs) between scalar triplets, some on the same
  // entries (the inertia before the blocks, a torque term after): every path — first build,
  // same sequence, another sequence over the same entries, a new structure — must equal
  // setFromTriplets of the expanded sequence bit for bit.
  std::mt19937 rng(4);
  std::uniform_int_distribution<int> body(0, 5);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  const int n = 36;
  Triplets t = RandomTriplets(n, 60, &rng);
  const size_t position = 40;
  std::vector<DenseBlock6> blocks(25);
  for (DenseBlock6& b : blocks) {
    b.row = 6 * body(rng);
    b.col = 6 * body(rng);
    for (double& x : b.v) x = value(rng);
  }
  auto expanded = [&] {
    Triplets e(t.begin(), t.begin() + position);
    for (const DenseBlock6& b : blocks)
      for (int c = 0; c < 6; ++c)
        for (int r = 0; r < 6; ++r) e.emplace_back(b.row + r, b.col + c, b.v[6 * c + r]);
    e.insert(e.end(), t.begin() + position, t.end());
    return e;
  };
  TripletAssembly assembly;
  Eigen::SparseMatrix<double> out;
  assembly.Assemble(t, blocks, position, n, &out);
  CHECK(BitwiseEqual(out, Reference(expanded(), n)));
  for (int round = 0; round < 3; ++round) {
    for (auto& e : t) e = Eigen::Triplet<double>(e.row(), e.col(), 1e3 * value(rng));
    for (DenseBlock6& b : blocks)
      for (double& x : b.v) x = value(rng);
    assembly.Assemble(t, blocks, position, n, &out);
    CHECK(BitwiseEqual(out, Reference(expanded(), n)));
  }
  CHECK(assembly.rebuilt() == 1);
  CHECK(assembly.reused() == 3);
  // The blocks reordered and one repeated: the same entries, scattered into the pattern.
  std::shuffle(blocks.begin(), blocks.end(), rng);
  blocks.push_back(blocks[3]);
  assembly.Assemble(t, blocks, position, n, &out);
  CHECK(BitwiseEqual(out, Reference(expanded(), n)));
  CHECK(assembly.reused() == 4);
  // The same entries and values with the blocks at another place in the sequence: the sums'
  // order changes, and so may their rounding; still setFromTriplets' own.
  assembly.Assemble(t, blocks, 10, n, &out);
  Triplets moved(t.begin(), t.begin() + 10);
  for (const DenseBlock6& b : blocks)
    for (int c = 0; c < 6; ++c)
      for (int r = 0; r < 6; ++r) moved.emplace_back(b.row + r, b.col + c, b.v[6 * c + r]);
  moved.insert(moved.end(), t.begin() + 10, t.end());
  CHECK(BitwiseEqual(out, Reference(moved, n)));
  CHECK(assembly.reused() == 5);
  // A block on an entry no one had: rebuilt, exact.
  std::vector<char> covered(n * n, 0);
  for (const auto& e : expanded()) covered[e.col() * n + e.row()] = 1;
  DenseBlock6 fresh;
  fresh.row = fresh.col = -1;
  for (int bc = 0; bc < 6 && fresh.row < 0; ++bc)
    for (int br = 0; br < 6 && fresh.row < 0; ++br)
      if (!covered[6 * bc * n + 6 * br]) {
        fresh.row = 6 * br;
        fresh.col = 6 * bc;
      }
  REQUIRE(fresh.row >= 0);
  for (double& x : fresh.v) x = value(rng);
  blocks.insert(blocks.begin() + 5, fresh);
  assembly.Assemble(t, blocks, position, n, &out);
  CHECK(BitwiseEqual(out, Reference(expanded(), n)));
  CHECK(assembly.rebuilt() == 2);
  // Without blocks, as the triplet-only call.
  blocks.clear();
  assembly.Assemble(t, blocks, position, n, &out);
  CHECK(BitwiseEqual(out, Reference(t, n)));
}

TEST_CASE("triplet assembly: a kept superset pattern holds the same values and explicit zeros",
          "[optim]") {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  const int n = 40;
  Triplets t = RandomTriplets(n, 500, &rng);
  // out's entries: ref's, bit for bit, and explicit zeros where ref has none.
  auto sameValues = [](const Eigen::SparseMatrix<double>& out,
                       const Eigen::SparseMatrix<double>& ref) {
    int matched = 0;
    for (int c = 0; c < out.outerSize(); ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator e(out, c); e; ++e) {
        const double r = ref.coeff(e.row(), e.col());
        if (std::memcmp(&r, &e.valueRef(), sizeof r) != 0 && !(r == 0.0 && e.value() == 0.0))
          return false;
        if (r != 0.0 || e.value() != 0.0) ++matched;
      }
    int refNonzero = 0;
    for (int c = 0; c < ref.outerSize(); ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator e(ref, c); e; ++e) refNonzero += e.value() != 0.0;
    return matched == refNonzero;
  };
  TripletAssembly assembly;
  assembly.SetKeepSuperset(true);
  Eigen::SparseMatrix<double> out;
  assembly.Assemble(t, n, &out);
  const Eigen::Index full = out.nonZeros();
  // Drop the triplets of a few entries (contacts that left): the pattern stays.
  auto dropEntry = [&](int k) {
    const int r = t[k].row(), c = t[k].col();
    t.erase(std::remove_if(t.begin(), t.end(),
                           [&](const Eigen::Triplet<double>& e) {
                             return e.row() == r && e.col() == c;
                           }),
            t.end());
  };
  for (int k = 0; k < 10; ++k) dropEntry(7 * k);
  for (auto& e : t) e = Eigen::Triplet<double>(e.row(), e.col(), value(rng));
  assembly.Assemble(t, n, &out);
  CHECK(assembly.rebuilt() == 1);
  CHECK(out.nonZeros() == full);
  CHECK(sameValues(out, Reference(t, n)));
  // The same sequence again: still exact (the missed entries zeroed again).
  for (auto& e : t) e = Eigen::Triplet<double>(e.row(), e.col(), value(rng));
  assembly.Assemble(t, n, &out);
  CHECK(assembly.rebuilt() == 1);
  CHECK(sameValues(out, Reference(t, n)));
  // Below kSupersetFill of the pattern: rebuilt to the exact structure.
  while (static_cast<double>(Reference(t, n).nonZeros()) >=
         TripletAssembly::kSupersetFill * static_cast<double>(full))
    dropEntry(0);
  assembly.Assemble(t, n, &out);
  CHECK(assembly.rebuilt() == 2);
  CHECK(BitwiseEqual(out, Reference(t, n)));
  // Without the option, any missed entry rebuilds.
  TripletAssembly exact;
  exact.Assemble(t, n, &out);
  dropEntry(3);
  exact.Assemble(t, n, &out);
  CHECK(exact.rebuilt() == 2);
  CHECK(BitwiseEqual(out, Reference(t, n)));
}
