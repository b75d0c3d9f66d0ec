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
  // Each shape is carried by its link; adjacent links' shapes, and one link's shapes among
  // themselves, do not touch (Scene::AttachToCarrier).
  for (LinkShape& s : shapes)
    if (!AddActor(std::move(s.kind), error, contactLayer, h).IsValid())
      return {};  // checked by BuildLinkShapes: not reached
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
