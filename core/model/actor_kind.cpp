#include "core/model/actor_kind.h"

#include <cmath>

#include "core/model/rigid_math.h"

namespace superdex {

bool ActorKind::HasFreeDof() const {
  for (int i = 0; i < NumTangentDofs(); ++i)
    if (!IsPrescribed(i)) return true;
  return false;
}

void ActorKind::DifferenceGroups(const KindState& s,
                                 std::vector<KindDifferenceGroup>* groups) const {
  const int n = static_cast<int>(s.x.size());
  KindDifferenceGroup g;
  for (int i = 0; i < 2 * n; ++i) {
    g.directions.push_back({{{i, 1.0}}, i >= n, 1.0});
    g.entries.push_back(i);
  }
  for (int i = 0; i < NumTangentDofs(); ++i)
    if (!IsPrescribed(i)) {
      g.tangentDofs.push_back(i);
      g.tangentLength.push_back(1.0);
    }
  groups->assign(1, std::move(g));
}

Eigen::MatrixXd ActorKind::CenterOfMassJacobian(const KindState& s) const {
  const int n = static_cast<int>(s.x.size());
  Eigen::MatrixXd C(3, n);
  KindState moved = s;
  for (int i = 0; i < n; ++i) {
    const double h = 1e-6 * (1.0 + std::abs(s.x[i]));
    moved.x[i] = s.x[i] + h;
    const Eigen::Vector3d plus = CenterOfMass(moved);
    moved.x[i] = s.x[i] - h;
    C.col(i) = (plus - CenterOfMass(moved)) / (2.0 * h);
    moved.x[i] = s.x[i];
  }
  return C;
}

bool ActorKind::IsCarried() const {
  const std::vector<CarriedPart>* parts = CarriedParts();
  return parts && !parts->empty();
}

bool ActorKind::FullyCarried() const {
  if (!IsCarried()) return false;
  int dofs = 0;
  for (const CarriedPart& p : *CarriedParts()) dofs += p.Size();
  return dofs == NumTangentDofs();
}

void AttachedConfiguration(const ActorKind& carrier, const std::vector<CarriedPart>& parts,
                           const Eigen::VectorXd& carrierQ, Eigen::VectorXd* q) {
  for (const CarriedPart& p : parts) {
    const int off = carrier.CarriedFrameOffset(p.frame);
    const Eigen::Matrix3d Rf = Matrix3At(carrierQ, off + 3);
    q->segment<3>(p.entry) = carrierQ.segment<3>(off) + Rf * p.offset;
    if (p.kind == CarriedPart::Kind::Pose) Matrix3At(q, p.entry + 3) = Rf * p.rotation;
  }
}

namespace {

// Empty when the carried parts lie inside q and δ, apart, and on no prescribed dof.
std::string ValidateCarriedParts(const ActorKind& kind, const std::string& name) {
  if (!kind.CarriedParts()) return {};
  const int n = kind.NumDofs(), m = kind.NumTangentDofs();
  std::vector<char> used(static_cast<size_t>(m), 0);
  for (const CarriedPart& p : *kind.CarriedParts()) {
    const int entries = p.kind == CarriedPart::Kind::Point ? 3 : 12;
    if (p.entry < 0 || p.entry + entries > n || p.dof < 0 || p.dof + p.Size() > m)
      return name + ": a carried part lies outside q or δ";
    for (int i = p.dof; i < p.dof + p.Size(); ++i) {
      if (used[i]) return name + ": carried parts overlap at tangent dof " + std::to_string(i);
      if (kind.IsPrescribed(i))
        return name + ": carried part on prescribed tangent dof " + std::to_string(i);
      used[i] = 1;
    }
  }
  return {};
}

}  // namespace

std::string ValidateKindLayout(const ActorKind& kind, const Eigen::Vector3d& gravity) {
  const std::string name = "actor (" + kind.KindName() + ")";
  if (std::string m = kind.Validate(); !m.empty()) return m;
  if (std::string m = Validate(kind.contact, "contact."); !m.empty()) return m;
  const int n = kind.NumDofs();
  if (n <= 0) return name + ": NumDofs must be > 0";
  const KindState s = kind.InitialState();
  if (s.x.size() != n || s.v.size() != n)
    return name + ": the initial state needs " + std::to_string(n) + " entries in x and v";
  if (!s.x.allFinite() || !s.v.allFinite()) return name + ": the initial state must be finite";
  const int m = kind.NumTangentDofs();
  if (m <= 0 || m > n) return name + ": NumTangentDofs must be in [1, NumDofs]";
  if (std::string e = ValidateCarriedParts(kind, name); !e.empty()) return e;
  {  // A stage load at the first stage's time: m finite entries.
    KindStageData stage;
    stage.dt = 1.0;
    stage.gravity = gravity;
    stage.qHat = stage.q0 = stage.qLast = s.x;
    Eigen::VectorXd f;
    if (kind.StageLoad(stage, &f) && (f.size() != m || !f.allFinite()))
      return name + ": StageLoad must give NumTangentDofs (" + std::to_string(m) +
             ") finite entries, got " + std::to_string(f.size());
  }
  // Blocks read by the contact assembler: whole 3-dof blocks of δ, prescribed all or none.
  auto badBlock = [&](int first) {
    if (first < 0 || first + 3 > m) return true;
    return kind.IsPrescribed(first) != kind.IsPrescribed(first + 1) ||
           kind.IsPrescribed(first) != kind.IsPrescribed(first + 2);
  };
  for (int k = 0; k < kind.NumSamples(); ++k) {
    const KindSample ks = kind.Sample(k, s.x);
    const std::string sample = name + ": sample " + std::to_string(k);
    if (ks.map.kind == SamplePointMap::Kind::Nodes && (ks.map.nodes < 1 || ks.map.nodes > 4))
      return sample + " needs a Nodes map of 1 to 4 nodes";
    for (int b = 0; b < ks.Blocks(); ++b)
      if (badBlock(ks.dof[b])) return sample + " reads a dof block outside δ or partly prescribed";
    if (!(ks.weight >= 0.0)) return name + ": sample weights must be >= 0";
    if (ks.hasNormal && !(std::abs(ks.n.norm() - 1.0) < 1e-9))
      return sample + ": its colliding normal must be a unit vector";
  }
  for (int b = 0; b < kind.NumSampleBodies(); ++b) {
    const std::string body = name + ": sample body " + std::to_string(b);
    int dof[2];
    kind.SampleBodyDofs(b, dof);
    if (!kind.SampleBody(b)) return body + " has no geometry (SampleBody is null)";
    if (badBlock(dof[0]) || badBlock(dof[1]) ||
        kind.IsPrescribed(dof[0]) != kind.IsPrescribed(dof[1]))
      return body + " reads a dof block outside δ or partly prescribed";
  }
  if (const RigidCollider* c = kind.Collider()) {
    // The assembler and the step limit take φ >= |Y| − boundingRadius (the shape within it).
    if (!(c->boundingRadius > 0.0))
      return name + ": the collider's boundingRadius must be > 0 (max |X| over its shape, m)";
    const KindFrame f = kind.ColliderFrame(s.x);
    if (f.rigid && f.blocks != 2)
      return name + ": a rigid collider frame moves with 2 blocks, [δp] and [δθ]";
    if (f.blocks < 0 || f.blocks > 4) return name + ": the collider frame moves with 0 to 4 blocks";
    if (!f.rigid && f.F.cols() != 3 * f.blocks)
      return name + ": the collider frame's Jacobian F must have 3 columns per block it moves with";
    if (!f.rigid && !f.F.bottomRows<3>().isZero())
      return name + ": a collider frame that rotates with a general map of the dofs is not supported yet";
    for (int b = 0; b < f.blocks; ++b)
      if (badBlock(f.dof[b]))
        return name + ": the collider frame reads a dof block outside δ or partly prescribed";
  }
  return {};
}

}  // namespace superdex
