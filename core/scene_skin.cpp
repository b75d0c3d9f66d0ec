// Carried actors on the scene: their check and attachment to a carrier, the automatic disabling
// of contact between actors on the same or adjacent frames, and a soft skin's bindings resolved
// into carried parts (Scene::AddSoftActor with SoftActorDesc::skin).
#include <cmath>
#include <set>

#include "core/model/rigid_math.h"
#include "core/scene.h"

namespace superdex {

bool Scene::CheckCarried(const ActorKind& kind, ActorHandle parent, Error* error) const {
  const std::string name = "actor (" + kind.KindName() + ")";
  if (!parent.IsValid())
    return Fail(error, name + ": an attached actor needs its carrier as parent");
  for (const CarriedPart& p : *kind.CarriedParts())
    if (actors_[parent.index].carrier >= 0 ||
        !(p.frame >= 0 && p.frame < Kind(parent).NumCarriedFrames()))
      return Fail(error, name + ": attachment frame " + std::to_string(p.frame) +
                             " is not a frame of its parent '" + ActorName(parent) + "'");
  return true;
}

namespace {

// The frames an actor's carried parts ride on.
std::set<int> FramesOf(const ActorKind& kind) {
  std::set<int> frames;
  for (const CarriedPart& p : *kind.CarriedParts()) frames.insert(p.frame);
  return frames;
}

}  // namespace

void Scene::AttachToCarrier(ActorHandle h, ActorHandle parent) {
  actors_[h.index].carrier = parent.index;
  SyncAttachedStates();
  // Actors on the same frame or on a frame and its parent (a link's shapes, adjacent links, a
  // skin and the links it binds) do not touch (spec: adjacent links and skinned parts).
  const ActorKind& carrier = Kind(parent);
  auto adjacent = [&](int f, int g) {
    return f == g || carrier.CarriedFrameParent(f) == g || carrier.CarriedFrameParent(g) == f;
  };
  const std::set<int> mine = FramesOf(Kind(h));
  for (int j = 0; j < h.index; ++j) {
    if (actors_[j].carrier != parent.index) continue;
    bool touching = false;
    for (int f : FramesOf(*kinds_[j]))
      for (int g : mine) touching = touching || adjacent(f, g);
    if (touching) DisableAdjacentContact({j}, h);
  }
}

namespace {

// Whether world point X lies within distance d [m] of attached body `body` (its field, at its
// state x = [p, vec R]).
bool NearShape(const ActorKind& body, const Eigen::VectorXd& x, const Eigen::Vector3d& X,
               double d) {
  const Eigen::Matrix3d R = Matrix3At(x, 3);
  return body.Collider()->Value(R.transpose() * (X - x.head<3>())) <= d;
}

}  // namespace

bool Scene::SkinParts(const SoftActorDesc& desc, const SoftKind& kind, ActorHandle skeleton,
                      std::vector<CarriedPart>* parts, Error* error) const {
  if (!skeleton.IsValid())
    return Fail(error, "skin: a soft-skinned actor needs its skeleton (an articulated actor) as "
                       "parent");
  const auto* arm = dynamic_cast<const ArticulatedKind*>(&Kind(skeleton));
  if (!arm)
    return Fail(error, "skin: the parent '" + ActorName(skeleton) +
                           "' is not an articulated actor (a skin's skeleton)");
  const Eigen::VectorXd& q = step_.vectorStates[skeleton.index].x;
  const std::vector<RigidPose> linkPose = arm->LinkPoses(q);
  const SoftBodyModel& m = kind.Model();
  const Eigen::VectorXd x = kind.InitialState().x;
  const int n = m.NumNodes();
  std::vector<int> constrainedBy(n, -1), boundBy(n, -1), linkOf(desc.skin.size(), -1);
  for (size_t j = 0; j < m.constraints.size(); ++j)
    for (int a : m.constraints[j].nodes) constrainedBy[a] = static_cast<int>(j);
  for (size_t i = 0; i < desc.skin.size(); ++i) {
    const SkinBinding& b = desc.skin[i];
    const std::string field = "skin[" + std::to_string(i) + "]";
    const int l = linkOf[i] = arm->FindLink(b.link);
    if (l < 0)
      return Fail(error, field + ".link: no link named \"" + b.link + "\" in '" +
                             ActorName(skeleton) + "'");
    if (b.hasRegion && !(b.regionMin.allFinite() && b.regionMax.allFinite() &&
                      (b.regionMin.array() < b.regionMax.array()).all()))
      return Fail(error, field + ".region: min must be finite and < max in every component");
    if (std::isnan(b.shapeDistance) || std::isinf(b.shapeDistance))
      return Fail(error, field + ".shape_distance: must be finite (< 0: not used)");
    std::vector<int> shapes;  // the link's shapes with a field
    if (b.shapeDistance >= 0.0) {
      for (int j = 0; j < NumActors(); ++j)
        if (actors_[j].carrier == skeleton.index && IsAttached({j}) && kinds_[j]->Collider() &&
            FramesOf(*kinds_[j]).count(l))
          shapes.push_back(j);
      if (shapes.empty())
        return Fail(error, field + ".shape_distance: link \"" + b.link +
                               "\" has no collision shape with a field");
    }
    std::vector<char> selected(n, 0);
    for (int a : b.nodes) {
      if (a < 0 || a >= n)
        return Fail(error, field + ".nodes: " + std::to_string(a) +
                               " is not a node of the mesh (0 .. " + std::to_string(n - 1) + ")");
      selected[a] = 1;
    }
    for (int a = 0; a < n; ++a) {
      const Eigen::Vector3d X = x.segment<3>(3 * a);
      const Eigen::Vector3d XL = linkPose[l].R.transpose() * (X - linkPose[l].p);
      if (b.hasRegion && (XL.array() >= b.regionMin.array()).all() &&
          (XL.array() <= b.regionMax.array()).all())
        selected[a] = 1;
      for (int j : shapes)
        if (NearShape(*kinds_[j], step_.vectorStates[j].x, X, b.shapeDistance)) selected[a] = 1;
    }
    int count = 0;
    for (int a = 0; a < n; ++a) {
      if (!selected[a]) continue;
      const std::string node = field + ": node " + std::to_string(a);
      if (constrainedBy[a] >= 0)
        return Fail(error, node + " is pinned or driven by constraints[" +
                               std::to_string(constrainedBy[a]) + "]; a bound node follows its link");
      if (boundBy[a] >= 0 && linkOf[boundBy[a]] != l)
        return Fail(error, node + " is bound to link \"" + desc.skin[boundBy[a]].link +
                               "\" by skin[" + std::to_string(boundBy[a]) + "] already");
      boundBy[a] = static_cast<int>(i);
      ++count;
    }
    if (count == 0)
      return Fail(error, field + ": binds no node (its nodes, region and shape distance select none)");
  }
  parts->clear();
  for (int a = 0; a < n; ++a) {
    if (boundBy[a] < 0) continue;
    CarriedPart p;
    p.kind = CarriedPart::Kind::Point;
    p.frame = linkOf[boundBy[a]];
    p.entry = p.dof = 3 * a;
    const int off = arm->CarriedFrameOffset(p.frame);
    p.offset = Matrix3At(q, off + 3).transpose() * (x.segment<3>(3 * a) - q.segment<3>(off));
    parts->push_back(p);
  }
  return true;
}

}  // namespace superdex
