// The cross-product matrix of a vector, for every layer above geometry (rotations, energies).
#pragma once

#include <Eigen/Core>

namespace superdex {

/// [v]× with [v]× w = v × w (inline: the contact sample loops call it per sample).
inline Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S(0, 0) = 0.0;    S(0, 1) = -v.z(); S(0, 2) = v.y();
  S(1, 0) = v.z();  S(1, 1) = 0.0;    S(1, 2) = -v.x();
  S(2, 0) = -v.y(); S(2, 1) = v.x();  S(2, 2) = 0.0;
  return S;
}

}  // namespace superdex
