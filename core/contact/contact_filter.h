// Contact filtering (spec: "Contact Filtering"): which ordered actor pairs (A colliding, B
// collider) are eligible. Two gates, both must allow a pair:
//   - layers: every actor has a string layer; EnableLayer(a, b, on) sets the ordered layer pair
//     (a colliding against b). Default: every layer pair enabled.
//   - actor pairs: EnableActors(A, B, on) sets the ordered actor pair. Default: enabled. It cannot
//     re-enable a pair its layers disable.
// Settings are ordered in time: a later setting of the same pair overrides an earlier one (the
// automatic disabling of adjacent links or skins included, which uses the same actor gate).
// Nested actors: each actor may have a parent; with includeNested, an actor resolves to itself
// plus all its descendants, and the setting applies to the cross-product of the two resolved sets
// (self-pairs included where the sets overlap), and to no other pair.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace superdex {

class ContactFilter {
 public:
  /// Registers actor `index` (0, 1, 2, ... in order) with its layer and parent (−1: none).
  void AddActor(const std::string& layer, int parent);
  int NumActors() const { return static_cast<int>(layerOf_.size()); }

  void SetLayer(int actor, const std::string& layer);
  const std::string& Layer(int actor) const { return layerOf_[actor]; }
  int Parent(int actor) const { return parent_[actor]; }

  void EnableLayer(const std::string& colliding, const std::string& collider, bool enable);
  /// Applies to the cross-product of the resolved sets of a and b.
  void EnableActors(int a, int b, bool enable, bool includeNested);

  /// The actor itself, then its descendants (depth first, in index order).
  std::vector<int> Resolve(int actor, bool includeNested) const;

  /// Whether the ordered pair (colliding a, collider b) is eligible.
  bool Allowed(int a, int b) const;

  /// The explicit settings in force, per ordered layer pair and per ordered actor pair (the
  /// later of two settings of a pair is the one kept): applied again in any order, they give
  /// this filter.
  const std::map<std::pair<std::string, std::string>, bool>& LayerSettings() const {
    return layers_;
  }
  const std::map<std::pair<int, int>, bool>& ActorSettings() const { return actors_; }

  /// Counts the changes: a user of Allowed may keep its answers while it stays the same.
  long Version() const { return version_; }

 private:
  long version_ = 0;
  std::vector<std::string> layerOf_;
  std::vector<int> parent_;
  std::vector<std::vector<int>> children_;
  std::map<std::pair<std::string, std::string>, bool> layers_;  // explicit settings only
  std::map<std::pair<int, int>, bool> actors_;                  // explicit settings only
};

}  // namespace superdex
