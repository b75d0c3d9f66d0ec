// Scene::AddArticulatedActor: an articulation and its links' collision shapes as attached actors.
#include <set>

#include "core/scene.h"

namespace superdex {

ActorHandle Scene::AddArticulatedActor(const ArticulatedActorDesc& desc, Error* error,
                                       const std::string& contactLayer, ActorHandle parent) {
  // Everything is built and checked before anything is added.
  if (!ValidParent(parent, error) || !UniqueName(desc.name, error)) return {};
  std::unique_ptr<ArticulatedKind> kind = ArticulatedKind::Build(desc, error);
  if (!kind) return {};
  std::vector<LinkShape> shapes;
  if (!BuildLinkShapes(desc, &shapes, error)) return {};
  std::set<std::string> names;
  for (const LinkShape& s : shapes)
    if (!UniqueName(s.kind->name, error) || !names.insert(s.kind->name).second ||
        s.kind->name == desc.name)
      return Fail(error, "articulation '" + desc.name + "': shape name '" + s.kind->name +
                             "' is not unique"),
             ActorHandle();
  const ActorHandle h = AddActor(std::move(kind), error, contactLayer, parent);
  if (!h.IsValid()) return h;
  std::vector<std::pair<int, ActorHandle>> bodies;  // (link, actor)
  for (LinkShape& s : shapes) {
    const ActorHandle b = AddActor(std::move(s.kind), error, contactLayer, h);
    if (!b.IsValid()) return b;  // checked by BuildLinkShapes: not reached
    bodies.push_back({s.link, b});
  }
  // Adjacent links' shapes, and one link's shapes among themselves, do not touch.
  const KinematicTree& t = static_cast<const ArticulatedKind&>(Kind(h)).Tree();
  for (size_t i = 0; i < bodies.size(); ++i)
    for (size_t j = i + 1; j < bodies.size(); ++j) {
      const int li = bodies[i].first, lj = bodies[j].first;
      if (li == lj || t.Joint(li).parent == lj || t.Joint(lj).parent == li)
        DisableAdjacentContact(bodies[i].second, bodies[j].second);
    }
  return h;
}

std::vector<ActorHandle> Scene::AttachedActors(ActorHandle carrier) const {
  std::vector<ActorHandle> out;
  for (int i = 0; i < NumActors(); ++i)
    if (actors_[i].carrier == carrier.index) out.push_back({i});
  return out;
}

const RigidBodyModel* Scene::BodyModel(ActorHandle a) const {
  if (actors_[a.index].rigid) return &Model(a);
  if (IsAttached(a)) return &static_cast<const AttachedBodyKind&>(Kind(a)).Model();
  return nullptr;
}

RigidBodyState Scene::BodyState(ActorHandle a) const {
  return RigidKind::Unpack(KindStateOf(a));
}

}  // namespace superdex
