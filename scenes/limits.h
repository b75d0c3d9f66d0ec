// The resource limits of scene files, runs and fits: an input beyond one is refused before any
// work starts, with the estimate and the limit in the message (docs/reliability.md). The figures
// behind them were measured on a 2-core machine with a Release build; the limits of mesh files
// and of the mesher are in geometry/mesh_limits.h.
#pragma once

namespace superdex::limits {

/// Bytes of a scene file. The parsed JSON takes about ten times its text; the largest shipped
/// scene is 5 KB (the 1005 actors of pile.json are grids).
inline constexpr double kMaxSceneFileBytes = 64.0 * 1024 * 1024;

/// Nesting depth of a JSON value (scene files, trajectory lines). The formats nest at most 6
/// levels; a deeper value is refused before it is built.
inline constexpr int kMaxJsonDepth = 64;

/// Actors of one scene, after grid replication. Loading cost about 0.18 ms and 2.6 KB per rigid
/// sphere (64 000 spheres: 11.5 s, 166 MB before the first step), so 1e5 actors are about 20 s
/// and 260 MB.
inline constexpr double kMaxActors = 1e5;
inline constexpr double kBytesPerActor = 2.6e3;

/// Tetrahedra over all soft actors of one scene. A soft box pressed on the ground needed about
/// 10 KB per tet (162 000 tets: 1.7 GB peak), so the limit is about 3 GB.
inline constexpr double kMaxSoftTets = 3e5;
inline constexpr double kBytesPerSoftTet = 10e3;

/// Steps of one run (duration / dt). The cheapest step measured, a free body, takes about 10 µs;
/// typical contact steps take 0.1 to 10 ms, so 1e8 steps are hours to weeks.
inline constexpr double kMaxSteps = 1e8;

/// The arrays Python's Scene.run records (14 numbers per actor and frame, allocated before the
/// first step) [bytes].
inline constexpr double kMaxRecordBytes = 4e9;

/// Steps of a fit or gradient run (the last observed time / dt). The adjoint pass keeps every
/// step's record: 1.5 KB per step for one rigid box, more with more actors and contacts.
inline constexpr double kMaxFitSteps = 1e6;
inline constexpr double kBytesPerFitStep = 1.5e3;

/// Largest |coordinate| and size in a scene file [m]: positions, radii, box sizes, mesh
/// coordinates after `scale`, edge lengths, grid replication. Beyond it the solver's absolute
/// tolerances lose their meaning (a soft sphere of radius 1e5 m did not finish 10 steps in 20 s)
/// and volumes, masses and inertias approach double's range.
inline constexpr double kMaxLength = 1e6;

}  // namespace superdex::limits
