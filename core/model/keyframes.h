// Quantities prescribed piecewise linearly in time (driven soft nodes, applied loads).
#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

namespace superdex {

/// A vector piecewise linear in time: keyframes (t [s], value) with increasing times. Before the
/// first keyframe its value holds, after the last the last one's; no keyframes: zero.
using VectorKeyframes = std::vector<std::pair<double, Eigen::Vector3d>>;
Eigen::Vector3d PiecewiseLinear(const VectorKeyframes& keys, double t);
/// "" when the keyframes are finite with increasing times, else a message naming `field`.
std::string CheckKeyframes(const VectorKeyframes& keys, const std::string& field);

/// A scalar piecewise linear in time (a joint's drive target), by the same rules.
using ScalarKeyframes = std::vector<std::pair<double, double>>;
double PiecewiseLinear(const ScalarKeyframes& keys, double t);
/// The path's slope at t [value/s]: the segment's after t (the last one's at the last keyframe),
/// 0 before the first keyframe and after the last.
double PiecewiseSlope(const ScalarKeyframes& keys, double t);
std::string CheckKeyframes(const ScalarKeyframes& keys, const std::string& field);

}  // namespace superdex
