// superdex_peer_bullet: runs a superdex reference scene in Bullet (btDiscreteDynamicsWorld with
// the sequential-impulse solver) and prints one JSON result line (wall time, metrics, failure).
//   superdex_peer_bullet --scene stack --dt 1e-2 [--duration S] [--iterations N]
#include <btBulletDynamicsCommon.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <vector>

#include "peer_run.h"

namespace sp = superdex::peers;

namespace {

btVector3 Bt(const Eigen::Vector3d& v) { return btVector3(v.x(), v.y(), v.z()); }
Eigen::Vector3d Eig(const btVector3& v) { return Eigen::Vector3d(v.x(), v.y(), v.z()); }

/// Owns the world and everything added to it.
struct World {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btDefaultMotionState>> states;
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  ~World() {
    for (auto& b : bodies) world.removeRigidBody(b.get());
  }
};

btCollisionShape* MakeShape(const sp::PeerBody& b) {
  switch (b.shape) {
    case sp::ShapeKind::Plane: return new btStaticPlaneShape(Bt(b.normal), b.normal.dot(b.position));
    case sp::ShapeKind::Box: return new btBoxShape(Bt(b.halfExtents));
    case sp::ShapeKind::Sphere: return new btSphereShape(b.radius);
  }
  return nullptr;
}

}  // namespace

int main(int argc, char** argv) {
  sp::PeerOptions o;
  sp::PeerScene scene;
  if (!sp::StartRun(argc, argv, &o, &scene)) return 2;
  const double duration = o.duration > 0 ? o.duration : scene.duration;

  World w;
  w.world.setGravity(Bt(scene.gravity));
  btContactSolverInfo& info = w.world.getSolverInfo();
  info.m_numIterations = o.iterations > 0 ? o.iterations : 50;
  info.m_splitImpulse = 1;  // Bullet's default: position correction without added energy

  // Bullet multiplies the two bodies' friction (and restitution): every body gets sqrt(mu) so
  // every pair, static or dynamic, has superdex's pair value mu.
  const double mu = scene.PairFriction();
  bool dissipative = mu > 0;
  for (const sp::PeerBody& b : scene.bodies) dissipative |= b.normalDamping > 0;
  const double restitution = dissipative ? 0.0 : 1.0;

  const int tracked = scene.LastDynamic();
  btRigidBody* trackedBody = nullptr;
  for (int i = 0; i < int(scene.bodies.size()); ++i) {
    const sp::PeerBody& b = scene.bodies[i];
    btCollisionShape* shape = MakeShape(b);
    w.shapes.emplace_back(shape);
    btTransform pose(btQuaternion(b.orientation.x(), b.orientation.y(), b.orientation.z(), b.orientation.w()),
                     Bt(b.shape == sp::ShapeKind::Plane ? Eigen::Vector3d::Zero() : b.position));
    w.states.emplace_back(new btDefaultMotionState(pose));
    const double mass = b.dynamic ? b.mass : 0.0;
    btRigidBody::btRigidBodyConstructionInfo ci(mass, w.states.back().get(), shape, Bt(b.inertia));
    ci.m_friction = std::sqrt(mu);
    ci.m_restitution = restitution;
    auto* body = new btRigidBody(ci);
    w.bodies.emplace_back(body);
    // Speculative contacts (Bullet's default: every manifold point, even at a positive distance,
    // enters the solver) stop a fast body at the surface a step early and lose its restitution;
    // where the bounce is the point (no dissipation), only touching contacts are solved.
    if (!dissipative) body->setContactProcessingThreshold(0.0);
    if (b.dynamic) {
      body->setActivationState(DISABLE_DEACTIVATION);  // no sleeping: drift stays measurable
      body->setLinearVelocity(Bt(b.velocity));
      body->setAngularVelocity(Bt(b.angularVelocity));
    }
    if (!b.collides) body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_NO_CONTACT_RESPONSE);
    if (!b.collides) w.world.addRigidBody(body, 0, 0);
    else w.world.addRigidBody(body);
    if (i == tracked) trackedBody = body;
  }

  sp::Recorder rec(scene, o, "bullet");
  double time = 0.0;
  auto sample = [&]() {
    sp::TrackSample x;
    x.t = time;
    x.p = Eig(trackedBody->getCenterOfMassPosition());
    const btQuaternion q = trackedBody->getOrientation();
    x.q = Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z());
    x.v = Eig(trackedBody->getLinearVelocity());
    x.w = Eig(trackedBody->getAngularVelocity());
    return x;
  };
  if (trackedBody) rec.Add(sample(), 0.0);
  const long steps = std::max(1L, std::lround(duration / o.dt));
  double wall = 0.0;
  for (long k = 0; k < steps; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    w.world.stepSimulation(o.dt, 0);  // maxSubSteps = 0: exactly one step of dt
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    time += o.dt;
    double pen = 0.0;  // manifolds of this step: the state at its start (the previous step's end)
    for (int m = 0; m < w.dispatcher.getNumManifolds(); ++m) {
      const btPersistentManifold* pm = w.dispatcher.getManifoldByIndexInternal(m);
      for (int c = 0; c < pm->getNumContacts(); ++c)
        pen = std::max(pen, double(-pm->getContactPoint(c).getDistance()));
    }
    if (trackedBody && !rec.Add(sample(), pen)) break;
  }
  nlohmann::json settings = {{"solver", "sequential impulse"},
                             {"iterations", info.m_numIterations},
                             {"split_impulse", bool(info.m_splitImpulse)},
                             {"erp", info.m_erp2}, {"cfm", info.m_globalCfm},
                             {"pair_friction", mu}, {"restitution", restitution},
                             {"double_precision", sizeof(btScalar) == 8},
                             {"collision_margin_box", 0.04}, {"deactivation", false},
                             {"speculative_contacts", dissipative}};
  rec.Print(wall, time, settings);
  return 0;
}
