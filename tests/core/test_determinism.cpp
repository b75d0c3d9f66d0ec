// Parallel contact evaluation is deterministic: the same states bit for bit with 1 and 2 threads.
#include <tbb/global_control.h>

#include <catch2/catch.hpp>
#include <cstring>

#include "core/scene.h"
#include "scene_builders.h"

using namespace superdex;

namespace {

std::vector<RigidBodyState> Run(int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  Scene scene;
  Error e;
  REQUIRE(scene.AddRigidActor(test::StaticGround(1e9, 0.5), &e).IsValid());
  // 200 spheres on a lattice, pressed 0.5 mm into each other and the ground: enough sample work
  // for the pipeline to evaluate pairs in parallel.
  for (int k = 0; k < 200; ++k) REQUIRE(scene.AddRigidActor(test::HeapSphere(k), &e).IsValid());
  for (int i = 0; i < 3; ++i) {
    StepReport r;
    REQUIRE(scene.Step(1e-2, &r, &e));
    REQUIRE(r.status == StageStatus::Converged);
  }
  std::vector<RigidBodyState> states;
  for (ActorHandle h : scene.RigidActors()) states.push_back(scene.State(h));
  return states;
}

}  // namespace

TEST_CASE("contact evaluation gives bit-identical results for 1 and 2 threads",
          "[core][determinism]") {
  const auto one = Run(1);
  const auto two = Run(2);
  REQUIRE(one.size() == two.size());
  for (size_t i = 0; i < one.size(); ++i) {
    INFO("actor " << i);
    CHECK(std::memcmp(one[i].p.data(), two[i].p.data(), sizeof(double) * 3) == 0);
    CHECK(std::memcmp(one[i].R.data(), two[i].R.data(), sizeof(double) * 9) == 0);
    CHECK(std::memcmp(one[i].v.data(), two[i].v.data(), sizeof(double) * 3) == 0);
  }
}
