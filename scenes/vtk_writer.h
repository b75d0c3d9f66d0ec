// Frames for ParaView: legacy VTK polydata of every actor's surface at the current state, with
// the contact traction field on soft surfaces, and of the contact samples with their tractions.
#pragma once

#include <string>

#include "core/scene.h"

namespace superdex {

/// Writes `path` (legacy ASCII VTK, POLYDATA): the boundary triangles of every soft actor at its
/// current node positions and the surfaces of rigid spheres, boxes and meshes at their poses
/// (planes are skipped). Cell data per triangle:
///   traction  the nominal contact traction on the face: force per reference area,
///             Σ_q w_q t_q / A_f [Pa] (world frame; soft faces; zero elsewhere), its normal part
///             and the last step's friction and damping (Scene::SoftFaceTractions)
///   pressure  the true contact pressure: −(normal force)/(current area) [Pa] (> 0 in
///             compression; it differs from −traction·n by the area change A_f / a_f)
///   actor     the actor index
/// Point data: displacement of soft nodes from their reference positions [m] (zero on rigid
/// surfaces). Returns false and fills *error when the file cannot be written.
bool WriteVtkFrame(Scene& scene, const std::string& path, Error* error);

/// Writes `path` (legacy ASCII VTK, POLYDATA of vertices): every active contact sample now
/// (Scene::ContactSamples), with point data on the colliding actor: normal_traction, friction and
/// damping (the last step's) [Pa], force w (t_n + t_f + t_d) [N] (the collider takes −force),
/// normal (the collider field's direction), phi [m], weight [m²], colliding and collider (actor
/// indices).
bool WriteVtkContacts(Scene& scene, const std::string& path, Error* error);

}  // namespace superdex
