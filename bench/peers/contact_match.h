// superdex's normal contact law, integrated over the contact shapes of the reference scenes,
// and the peer contact settings derived from it (see README.md, "Parameter mapping").
#pragma once

#include "peer_scene.h"

namespace superdex::peers {

/// Pressure k h h' of superdex's penalty at signed distance phi [Pa] (the C² ramp of
/// energies/penalty_ramp.h: h = s³(4ε − s)/(16ε³) for s = δ − φ in (0, 2ε), linear beyond).
double SuperdexPressure(double phi, double k, double eps, double delta);

/// Normal force of a flat face of area `area` at distance phi [N].
double FlatForce(double phi, double area, const PeerBody& b);
/// Normal force of a sphere whose lowest point is at distance phi above a plane [N].
double SphereForce(double phi, const PeerBody& b);

/// Linearized normal stiffness [N/m] of a body resting under its weight m g on a plane
/// (a box on its face, a sphere on its pole) with superdex's law.
double RestStiffness(const PeerBody& b, double g);

/// Peak penetration −φ_min [m] of a sphere dropped from height H (its lowest point above the
/// plane) onto a plane with superdex's law and no damping: the work of the contact force from
/// φ = δ down to φ_min equals m g (H − φ_min).
double DropPeakPenetration(const PeerBody& b, double height, double g);

}  // namespace superdex::peers
