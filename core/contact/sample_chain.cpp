#include "core/contact/sample_chain.h"

#include <Eigen/Geometry>

#include "core/model/rigid_math.h"

namespace superdex {

void RigidPullbackStencil(const Eigen::Matrix3d& RB, const Eigen::Vector3d& d,
                          const Eigen::Vector3d& gY, const Eigen::Matrix3d* HY, bool bDynamic,
                          PointStencil* out) {
  out->colliderDofs = bDynamic ? 6 : 0;
  const Eigen::Vector3d n = RB * gY;
  out->g.head<3>() = n;
  if (bDynamic) {
    out->g.segment<3>(3) = -n;
    out->g.segment<3>(6) = -d.cross(n);
  }
  if (!HY) return;
  const Eigen::Matrix3d Hw = RB * (*HY) * RB.transpose();
  auto& H = out->H;
  H.topLeftCorner<3, 3>() = Hw;
  if (!bDynamic) return;
  const Eigen::Matrix3d Kd = Skew(d);
  const Eigen::Matrix3d HKd = Hw * Kd;
  const Eigen::Matrix3d Nx = Skew(n);
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  // J_pᵀ H_w J_p with J_p = [I, −I, [d]×].
  H.block<3, 3>(0, 3) = -Hw;
  H.block<3, 3>(0, 6) = HKd + Nx.transpose();
  H.block<3, 3>(3, 0) = -Hw;
  H.block<3, 3>(3, 3) = Hw;
  H.block<3, 3>(3, 6) = -HKd - Nx.transpose();
  H.block<3, 3>(6, 0) = HKd.transpose() + Nx;
  H.block<3, 3>(6, 3) = -HKd.transpose() - Nx;
  H.block<3, 3>(6, 6) = Kd.transpose() * HKd + 0.5 * (n * d.transpose() + d * n.transpose()) -
                        n.dot(d) * I;
}

void ChainToActor(const SamplePointMap& map, const PointStencil& point, double w,
                  StencilVector* g, StencilMatrix* H) {
  const int nA = map.Dofs();
  const int nB = point.colliderDofs;
  const Eigen::Vector3d gy = w * point.g.head<3>();
  if (map.kind == SamplePointMap::Kind::Rigid) {
    g->segment<3>(0) += gy;
    g->segment<3>(3) += map.r.cross(gy);
  } else {
    for (int a = 0; a < map.nodes; ++a) g->segment<3>(3 * a) += map.bary[a] * gy;
  }
  if (nB > 0) g->segment(nA, nB) += w * point.g.segment(3, nB);
  if (!H) return;
  // Jᵀ M for a 3-row block M: rigid [M; [r]× M] (−[r]×ᵀ = [r]×), nodes [b_a M].
  const Eigen::Matrix3d Hyy = w * point.H.topLeftCorner<3, 3>();
  if (map.kind == SamplePointMap::Kind::Rigid) {
    const Eigen::Matrix3d Kr = Skew(map.r);
    const Eigen::Matrix3d HKt = Hyy * Kr.transpose();  // H J_θ, J_θ = −[r]× = [r]×ᵀ
    H->block<3, 3>(0, 0) += Hyy;
    H->block<3, 3>(0, 3) += HKt;
    H->block<3, 3>(3, 0) += HKt.transpose();
    H->block<3, 3>(3, 3) += Kr * HKt + 0.5 * (gy * map.r.transpose() + map.r * gy.transpose()) -
                            gy.dot(map.r) * Eigen::Matrix3d::Identity();
    if (nB > 0) {
      const Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 12> HyB =
          w * point.H.block(0, 3, 3, nB);
      const Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 12> KrHyB = Kr * HyB;
      H->block(0, nA, 3, nB) += HyB;
      H->block(3, nA, 3, nB) += KrHyB;
      H->block(nA, 0, nB, 3) += HyB.transpose();
      H->block(nA, 3, nB, 3) += KrHyB.transpose();
    }
  } else {
    for (int a = 0; a < map.nodes; ++a) {
      for (int c = 0; c < map.nodes; ++c)
        H->block<3, 3>(3 * a, 3 * c) += (map.bary[a] * map.bary[c]) * Hyy;
      if (nB > 0) {
        H->block(3 * a, nA, 3, nB) += (w * map.bary[a]) * point.H.block(0, 3, 3, nB);
        H->block(nA, 3 * a, nB, 3) += (w * map.bary[a]) * point.H.block(3, 0, nB, 3);
      }
    }
  }
  if (nB > 0) H->block(nA, nA, nB, nB) += w * point.H.block(3, 3, nB, nB);
}

}  // namespace superdex
