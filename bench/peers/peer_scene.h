// The subset of a superdex scene file that the peer adapters rebuild in MuJoCo and Bullet:
// rigid actors with plane, box or sphere shapes, their mass, pose, velocities and contact
// parameters, grid replication (same seed and jitter as scenes/scene_file.cpp), gravity.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace superdex::peers {

enum class ShapeKind { Plane, Box, Sphere };

/// One rigid body, in world coordinates, with superdex's per-actor contact parameters.
struct PeerBody {
  std::string name;
  ShapeKind shape = ShapeKind::Sphere;
  bool dynamic = true;
  bool collides = true;                          ///< collider_type is not "None"
  Eigen::Vector3d halfExtents = Eigen::Vector3d::Zero();  ///< box [m]
  double radius = 0.0;                           ///< sphere [m]
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();      ///< plane, world frame
  double mass = 0.0;                             ///< [kg] (dynamic bodies)
  Eigen::Vector3d inertia = Eigen::Vector3d::Zero();      ///< principal, body frame [kg m²]
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d angularVelocity = Eigen::Vector3d::Zero();  ///< world frame [rad/s]
  double mu = 0.5;                               ///< coulomb_friction_coefficient
  double normalDamping = 0.0;                    ///< normal_viscous_damping_coefficient [s/m]
  double k = 1e9;                                ///< penalty_coefficient [Pa/m]
  double eps = 0.005;                            ///< penalty_smoothing_half_distance [m]
  double delta = 0.001;                          ///< penalty_threshold_default [m]
};

struct PeerScene {
  std::string name;  ///< file stem: drop, incline, incline_creep, stack, pile, tumble
  Eigen::Vector3d gravity = Eigen::Vector3d(0, 0, -9.81);
  double duration = 1.0;
  std::vector<PeerBody> bodies;

  int LastDynamic() const;  ///< index of the last dynamic body (the tracked one), or -1
  /// Pair friction by superdex's rule (geometric mean) for the first dynamic body against the
  /// first static one; what each engine's per-body values are set to reproduce.
  double PairFriction() const;
};

/// Loads SCENE (a path ending in .json, or a name looked up in scenes/data/ of the source tree).
bool LoadPeerScene(const std::string& scene, PeerScene* out, std::string* error);

}  // namespace superdex::peers
