#include "core/sensitivity/adjoint.h"

#include <chrono>
#include <cmath>
#include <sstream>

#include "core/sensitivity/step_linearization.h"

namespace superdex {

bool AdjointSensitivity::Run(Scene* scene, const std::vector<double>& dts,
                             std::vector<StepReport>* reports, Error* error) {
  const auto t0 = std::chrono::steady_clock::now();
  scene_ = scene;
  dts_.clear();
  checkpoints_.clear();
  if (reports) reports->clear();
  checkpoints_.push_back(scene->Save());
  for (size_t n = 0; n < dts.size(); ++n) {
    StepReport rep;
    if (!scene->Step(dts[n], &rep, error)) return false;
    if (reports) reports->push_back(rep);
    if (rep.status != StageStatus::Converged) {
      std::ostringstream s;
      s << "step " << n << ": a stage did not converge (" << rep.message
        << "): no gradient is defined through it";
      return Fail(error, s.str());
    }
    dts_.push_back(dts[n]);
    checkpoints_.push_back(scene->Save());
  }
  runSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return true;
}

bool AdjointSensitivity::Gradient(const std::vector<SceneParameter>& parameters,
                                  const LossGradient& loss, Eigen::VectorXd* gradient,
                                  Error* error) {
  if (!scene_ || checkpoints_.empty()) return Fail(error, "adjoint: call Run first");
  const auto t0 = std::chrono::steady_clock::now();
  Scene& scene = *scene_;
  const int N = Steps();
  const int P = static_cast<int>(parameters.size());
  // Model parameters in the order the linearizer sees them.
  std::vector<int> modelIndex;
  scene.Restore(checkpoints_[0]);
  for (int j = 0; j < P; ++j) {
    if (!CheckDifferentiable(scene, parameters[j], j, error)) return false;
    if (!parameters[j].IsInitialState()) modelIndex.push_back(j);
  }
  gradient->setZero(P);
  injectRuns_ = 0;
  maxColors_ = 0;
  const int ns = scene.StateSize();
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(ns), previous, gTheta;
  scene.Restore(checkpoints_[N]);
  loss(N, scene, &lambda);
  StepLinearizer linearizer;
  bool ok = true;
  for (int n = N - 1; n >= 0 && ok; --n) {
    scene.Restore(checkpoints_[n]);
    ok = linearizer.Linearize(&scene, dts_[n], parameters, nullptr, error);
    if (!ok) {
      if (error) error->message = "step " + std::to_string(n) + ": " + error->message;
      break;
    }
    injectRuns_ += linearizer.Runs();
    maxColors_ = std::max(maxColors_, linearizer.Colors());
    linearizer.Adjoint(lambda, &previous, &gTheta);
    for (size_t k = 0; k < modelIndex.size(); ++k) (*gradient)[modelIndex[k]] += gTheta[k];
    scene.Restore(checkpoints_[n]);
    loss(n, scene, &previous);
    lambda.swap(previous);
  }
  if (ok) {
    scene.Restore(checkpoints_[0]);
    for (int j = 0; j < P; ++j)
      if (parameters[j].IsInitialState())
        (*gradient)[j] += InitialStateDirection(scene, parameters[j]).dot(lambda);
  }
  scene.Restore(checkpoints_[N]);
  gradientSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return ok;
}

}  // namespace superdex
