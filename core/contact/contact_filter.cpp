#include "core/contact/contact_filter.h"

namespace superdex {

void ContactFilter::AddActor(const std::string& layer, int parent) {
  ++version_;
  layerOf_.push_back(layer);
  parent_.push_back(parent);
  children_.emplace_back();
  if (parent >= 0) children_[parent].push_back(NumActors() - 1);
}

void ContactFilter::SetLayer(int actor, const std::string& layer) {
  ++version_;
  layerOf_[actor] = layer;
}

void ContactFilter::EnableLayer(const std::string& colliding, const std::string& collider,
                                bool enable) {
  ++version_;
  layers_[{colliding, collider}] = enable;
}

std::vector<int> ContactFilter::Resolve(int actor, bool includeNested) const {
  std::vector<int> out = {actor};
  if (!includeNested) return out;
  for (size_t k = 0; k < out.size(); ++k)
    for (int c : children_[out[k]]) out.push_back(c);
  return out;
}

void ContactFilter::EnableActors(int a, int b, bool enable, bool includeNested) {
  ++version_;
  for (int i : Resolve(a, includeNested))
    for (int j : Resolve(b, includeNested)) actors_[{i, j}] = enable;
}

bool ContactFilter::Allowed(int a, int b) const {
  if (!layers_.empty()) {
    const auto it = layers_.find({layerOf_[a], layerOf_[b]});
    if (it != layers_.end() && !it->second) return false;
  }
  if (!actors_.empty()) {
    const auto it = actors_.find({a, b});
    if (it != actors_.end() && !it->second) return false;
  }
  return true;
}

}  // namespace superdex
