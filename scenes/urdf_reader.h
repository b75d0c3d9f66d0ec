// URDF robots as articulated actors (liburdfdom's parser; docs/articulated.md, "URDF").
#pragma once

#include <map>
#include <string>

#include "core/model/articulated_kind.h"
#include "core/model/error.h"

namespace superdex {

/// How a URDF robot is placed: its root link joined to the world by a Fixed or a Free joint at a
/// pose, and initial joint values by URDF joint name.
struct UrdfPlacement {
  bool freeBase = false;                 ///< Free root joint (a floating base), else Fixed
  RigidPose base;                        ///< the root link's frame in the world
  std::map<std::string, double> jointPositions;   ///< per 1-dof joint [rad or m]
  std::map<std::string, double> jointVelocities;  ///< per 1-dof joint [rad/s or m/s]
  std::map<std::string, JointParams> jointParams; ///< replace the URDF's limits and damping
  /// Collision geometry: read (each <collision> a shape of its link) or ignored; the shapes'
  /// contact role (all alike); the largest spacing [m] of a box's or cylinder's colliding
  /// samples (a box's divisions per edge and a cylinder's rows follow from it).
  bool collisions = true;
  ContactParams contact;
  ColliderType colliderType = ColliderType::Auto;
  ActorBoundaryElementType boundaryElementType = ActorBoundaryElementType::P1Q3;
  double sampleSpacing = 0.01;
  /// A <cylinder> as a closed triangle mesh of 24 segments (false), or as the capsule of its
  /// radius and total length (true: its straight part the length less 2 r, which must be > 0).
  bool cylindersAsCapsules = false;
  /// Where mesh files are found (relative <mesh filename>s); ReadUrdfFile: the file's folder.
  std::string meshDirectory;
};

/// Reads a URDF document (`text`; `source` names it in messages, e.g. the file) into an
/// articulated description: one link per URDF link, parents first; revolute (limits), continuous,
/// prismatic (limits) and fixed joints with their origins and axes; <dynamics damping> as joint
/// damping; <inertial> origin, mass and inertia (a link without one has mass 0); each
/// <collision> (box, sphere, cylinder as a closed triangle mesh of 24 segments or a capsule, mesh files
/// with their scale) as a shape of its link at its <origin> (placement.collisions); visual
/// geometry is ignored. The root joins the world as `placement` says. False with *error
/// "<source>: <element> '<name>': <problem>" for: XML that does not parse (the parser's
/// message), floating and planar joints, mimic joints, a zero axis, limits with lower > upper, a
/// negative mass, placement entries naming no 1-dof joint, a mesh file that cannot be read or a
/// package:// URI (not resolved: give a path relative to the URDF file).
bool ReadUrdf(const std::string& text, const std::string& source, const UrdfPlacement& placement,
              ArticulatedActorDesc* out, Error* error);
/// The same from a file (its path names it).
bool ReadUrdfFile(const std::string& path, const UrdfPlacement& placement,
                  ArticulatedActorDesc* out, Error* error);

}  // namespace superdex
