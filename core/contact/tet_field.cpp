#include "core/contact/tet_field.h"

#include <Eigen/LU>
#include <cmath>

namespace superdex {

bool PullbackThrough(const SoftBodyModel& m, const Eigen::VectorXd& x, int t,
                     const Eigen::Vector3d& y, TetPullback* pb) {
  const Eigen::Vector4i& T = m.rest.tets[t];
  const Eigen::Vector3d x0 = x.segment<3>(3 * T[0]);
  Eigen::Matrix3d Ds;
  Ds << x.segment<3>(3 * T[1]) - x0, x.segment<3>(3 * T[2]) - x0, x.segment<3>(3 * T[3]) - x0;
  const double det = Ds.determinant();
  if (!(std::isfinite(det) && det > 0.0)) return false;
  pb->tet = t;
  pb->B = Ds.inverse();
  const Eigen::Vector3d beta = pb->B * (y - x0);
  pb->lambda << 1.0 - beta.sum(), beta;
  const Eigen::Matrix3d& DmInv = m.elements[t].DmInv;
  const Eigen::Matrix3d Dm = DmInv.inverse();
  pb->X = m.rest.vertices[T[0]] + Dm * beta;
  pb->Finv = Dm * pb->B;
  pb->F = Ds * DmInv;
  return true;
}

void TetPullbackStencil(const TetPullback& pb, const Eigen::Vector3d& gX,
                        const Eigen::Matrix3d* HX, PointStencil* out) {
  using Vec15 = Eigen::Matrix<double, 15, 1>;
  out->colliderDofs = 12;
  Eigen::Matrix<double, 3, 15> R;
  R.leftCols<3>().setIdentity();
  for (int a = 0; a < 4; ++a)
    R.middleCols<3>(3 + 3 * a) = -pb.lambda[a] * Eigen::Matrix3d::Identity();
  const Eigen::Matrix<double, 3, 15> J = pb.Finv * R;
  out->g = J.transpose() * gX;
  if (!HX) return;
  Eigen::Matrix<double, 15, 15>& Hz = out->H;
  Hz = J.transpose() * (*HX) * J;
  const Eigen::Vector3d c = pb.Finv.transpose() * gX;
  Eigen::Matrix<double, 4, 3> L;
  L.bottomRows<3>() = pb.B;
  L.row(0) = -pb.B.colwise().sum();
  for (int a = 0; a < 4; ++a) {
    const Vec15 u = R.transpose() * L.row(a).transpose();
    // v_a = c at the x_a block: u vᵀ touches only the columns of that block.
    Hz.middleCols<3>(3 + 3 * a) -= u * c.transpose();
    Hz.middleRows<3>(3 + 3 * a) -= c * u.transpose();
  }
}

Eigen::Vector3d ReferenceNormal(const TetPullback& pb, const Eigen::Vector3d& n) {
  const Eigen::Vector3d v = pb.F.transpose() * n;
  const double norm = v.norm();
  return norm > 0 ? Eigen::Vector3d(v / norm) : Eigen::Vector3d::Zero();
}

void TetFieldSide::FormBoxes() {
  box = SoftBounds(*x);
  boxLast = SoftBounds(*xLast);
  box.Inflate(1e-9);
  boxLast.Inflate(1e-9);
}

}  // namespace superdex
