#include "core/sensitivity/step_linearization.h"

#include "core/model/rigid_math.h"
#include "core/sensitivity/scene_replica.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

namespace superdex {
namespace {

// One difference direction: z (or parameter) moved by step × `move`; the directional derivative
// D is entered into the partials' columns as D × `spread`.
struct Direction {
  std::vector<std::pair<int, double>> move, spread;
  double step = 0.0;
};

// A group of an actor's coordinates (a rigid body, a soft node) as the differences see it: the
// directions of its local coordinates and of its own contact parameters, and the units (bodies
// and nodes) whose rows its moves reach.
struct Mover {
  std::vector<Direction> directions, parameters;
  std::vector<int> reach;
  bool alone = false;  // no free tangent dof (a prescribed node): no column in J_i, moved by itself
};

// Greedy distance-2 colouring: two movers share a colour only if no unit is reached by both.
// Sorts each mover's reach; returns the colour classes, the movers that must move alone last,
// each in a class of its own.
std::vector<std::vector<int>> ColourMovers(std::vector<Mover>* moversPtr) {
  std::vector<Mover>& movers = *moversPtr;
  const int U = static_cast<int>(movers.size());
  std::vector<std::vector<int>> reachedBy(U);
  for (int u = 0; u < U; ++u) {
    std::vector<int>& r = movers[u].reach;
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
    for (int w : r) reachedBy[w].push_back(u);
  }
  std::vector<int> color(U, -1), stamp;
  std::vector<std::vector<int>> members;
  for (int u = 0; u < U; ++u) {
    if (movers[u].alone) continue;
    for (int w : movers[u].reach)
      for (int v : reachedBy[w])
        if (color[v] >= 0) stamp[color[v]] = u;
    int c = 0;
    while (c < static_cast<int>(stamp.size()) && stamp[c] == u) ++c;
    if (c == static_cast<int>(stamp.size())) {
      stamp.push_back(-1);
      members.emplace_back();
    }
    color[u] = c;
    members[c].push_back(u);
  }
  for (int u = 0; u < U; ++u)
    if (movers[u].alone) members.push_back({u});
  return members;
}



// The sizes of one recorded step's linearization: s stages of nd dofs, a packed state of ns
// entries, P model parameters; z = [S_n, δ_0 … δ_{s−1}] has zSize entries, the outputs
// [ρ_0 … ρ_{s−1}, S_{n+1}] m.
struct StepSizes {
  int s, nd, ns, P, zSize, m;
};

StepSizes SizesOf(const Scene& scene, const StepTape& tape, const Eigen::VectorXd& S0,
                  const std::vector<SceneParameter>& model) {
  const int s = tape.used, nd = scene.StageDofs(), ns = static_cast<int>(S0.size());
  return {s, nd, ns, static_cast<int>(model.size()), ns + s * nd, s * nd + ns};
}

// The movers of the generic layer's actors: their kinds' groups (ActorKind::DifferenceGroups),
// each state block's directions at that block's state; a direction's derivative is spread back
// over its entries as D dᵀ/|d|² (the directions of a group are orthogonal). Returns, per actor,
// the mover of a kind of one group (−1 otherwise): its contact parameters move with it.
std::vector<int> AddKindMovers(Scene& scene, const Eigen::VectorXd& S0, const StepSizes& z,
                               int blocks, double h, double dt, std::vector<Mover>* movers,
                               std::vector<int>* rowUnit, std::vector<int>* dofUnit) {
  const int s = z.s, nd = z.nd, ns = z.ns, blockSize = ns / blocks;
  std::vector<int> moverOfKind(scene.NumActors(), -1);
  for (int a = 0; a < scene.NumActors(); ++a) {
    const ActorKind& kind = scene.Kind({a});
    const int n = kind.NumDofs(), o = scene.StateOffset({a});
    const std::vector<int>& stageDof = scene.KindStageDofs({a});
    std::vector<std::vector<KindDifferenceGroup>> groups(blocks);
    for (int b = 0; b < blocks; ++b)
      kind.DifferenceGroups(
          KindState{S0.segment(b * blockSize + o, n), S0.segment(b * blockSize + o + n, n)},
          &groups[b]);
    for (size_t g = 0; g < groups[0].size(); ++g) {
      const int u = static_cast<int>(movers->size());
      Mover mv;
      for (int b = 0; b < blocks; ++b) {
        if (g >= groups[b].size()) continue;
        for (const KindDifferenceGroup::Direction& d : groups[b][g].directions) {
          Direction dir;
          double norm2 = 0.0;
          for (const auto& [e, w] : d.entries) norm2 += w * w;
          for (const auto& [e, w] : d.entries) {
            dir.move.emplace_back(b * blockSize + o + e, w);
            dir.spread.emplace_back(b * blockSize + o + e, w / norm2);
          }
          dir.step = h / (d.length * (d.velocity ? dt : 1.0));
          mv.directions.push_back(std::move(dir));
        }
      }
      const KindDifferenceGroup& group = groups[0][g];
      for (int e : group.entries)
        for (int b = 0; b < blocks; ++b) (*rowUnit)[s * nd + b * blockSize + o + e] = u;
      mv.alone = true;
      for (int t : group.tangentDofs)
        if (stageDof[t] >= 0) (*dofUnit)[stageDof[t]] = u, mv.alone = false;
      for (int st = 0; st < s; ++st)
        for (size_t t = 0; t < group.tangentDofs.size(); ++t) {
          const int dof = stageDof[group.tangentDofs[t]];
          if (dof < 0) continue;
          const int column = ns + st * nd + dof;
          mv.directions.push_back({{{column, 1.0}}, {{column, 1.0}}, h / group.tangentLength[t]});
          (*rowUnit)[st * nd + dof] = u;
        }
      if (groups[0].size() == 1 && !mv.alone) moverOfKind[a] = u;
      movers->push_back(std::move(mv));
    }
  }
  return moverOfKind;
}

// The movers of one recorded step's differences, the unit of each output row (ρ_i rows by dof,
// S_{n+1} rows by state entry), their colour classes, the model parameters moved alone and every
// parameter's difference step.
struct MoverLayout {
  double h = 0.0;  // the state step of the differences
  std::vector<Mover> movers;
  std::vector<int> rowUnit;
  std::vector<std::vector<int>> members;
  std::vector<int> aloneParameters;
  std::vector<double> parameterStep;
};

MoverLayout LayOutMovers(Scene& scene, const StepTape& tape,
                         const std::vector<SceneParameter>& model, const Eigen::VectorXd& S0,
                         double dt) {
  const StepSizes z = SizesOf(scene, tape, S0, model);
  const int s = z.s, nd = z.nd, P = z.P, zSize = z.zSize, m = z.m;
  MoverLayout out;
  // The movers, and the unit of each output row (ρ_i rows by dof, S_{n+1} rows by state entry).
  const int blocks = 1 + scene.HistoryBlocks();
  // Half the forward replay's state step (core/sensitivity/sensitivity.cpp): a column moves one coordinate
  // of a body, the replay a whole sensitivity direction. Measured on the four-box stack under six
  // integrators and both modes (tests/core/test_adjoint.cpp), mean error against trajectory
  // differences: 7.7e-6 at a quarter, 8.0e-6 at half, 1.7e-5 at the full step, 1.7e-4 at twice it.
  const double h = 0.5 * DifferenceStateStep(scene, dt);
  std::vector<Mover> movers;
  std::vector<int> rowUnit(m, -1), dofUnit(nd, -1);
  const std::vector<int> moverOfKind =
      AddKindMovers(scene, S0, z, blocks, h, dt, &movers, &rowUnit, &dofUnit);
  const int U = static_cast<int>(movers.size());

  // Reach: the units coupled in any stage's Jacobian (column unit reaches row unit), and itself.
  for (int u = 0; u < U; ++u) movers[u].reach.push_back(u);
  for (int st = 0; st < s; ++st) {
    const Eigen::SparseMatrix<double>& J = tape.stages[st].jacobian;
    for (int c = 0; c < J.outerSize(); ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator e(J, c); e; ++e)
        movers[dofUnit[c]].reach.push_back(dofUnit[e.row()]);
  }
  const std::vector<std::vector<int>> members = ColourMovers(&movers);

  // Model parameters of a dynamic rigid actor, or of a kind's actor of one group, reach the rows
  // its mover reaches (the pair values of its contacts): they are moved with its colour. Others
  // (static and soft actors') alone.
  std::vector<std::vector<int>> owned(U);
  std::vector<int> aloneParameters;
  {
    const std::vector<int>& moverOfActor = moverOfKind;
    for (int p = 0; p < P; ++p) {
      const int mover = moverOfActor[model[p].actor.index];
      if (mover >= 0 && model[p].kind <= SceneParameterKind::FrictionFalloffVel)
        owned[mover].push_back(p);
      else
        aloneParameters.push_back(p);
    }
  }
  std::vector<double> parameterStep(P);
  for (int p = 0; p < P; ++p) parameterStep[p] = 1e-4 * std::abs(ParameterValue(scene, model[p]));
  for (int u = 0; u < U; ++u)
    for (int p : owned[u])
      movers[u].parameters.push_back({{{zSize + p, 1.0}}, {{zSize + p, 1.0}}, parameterStep[p]});

  out.h = h;
  out.movers = std::move(movers);
  out.rowUnit = std::move(rowUnit);
  out.members = members;
  out.aloneParameters = std::move(aloneParameters);
  out.parameterStep = std::move(parameterStep);
  return out;
}

// Runs of the recorded step in Inject mode, with z and the model parameters moved by a job's moves
// (z index, or zSize + parameter index; amount), each job one Richardson-extrapolated central
// difference. The runs are independent: each thread works on its own copy of the scene (made on
// first use, with the recorded stage solutions), and every result is attributed afterwards in a
// fixed order, so the partials do not depend on the number of threads.
class InjectRuns {
 public:
  using Moves = std::vector<std::pair<int, double>>;
  InjectRuns(const Scene& scene, const StepTape& tape, const Scene::Snapshot& before,
             const Eigen::VectorXd& S0, const std::vector<SceneParameter>& model, double dt)
      : scene_(scene), tape_(tape), before_(before), S0_(S0), model_(model), dt_(dt),
        s_(tape.used), nd_(scene.StageDofs()), ns_(static_cast<int>(S0.size())),
        zSize_(ns_ + s_ * nd_), m_(s_ * nd_ + ns_) {}

  /// Runs the jobs in parallel: (*results)[k] for jobs[k]; false on the first failure, with its
  /// message in *error. Adds the runs made to *runs.
  bool RunJobs(const std::vector<Moves>& jobs, std::vector<Eigen::VectorXd>* resultsPtr,
               int* runs, Error* error) {
    std::vector<Eigen::VectorXd>& results = *resultsPtr;
    results.assign(jobs.size(), Eigen::VectorXd());
    std::vector<char> ok(jobs.size(), 0);
    tbb::parallel_for(size_t(0), jobs.size(), [&](size_t k) {
      SceneReplica& rep = Replica();
      ok[k] = Richardson(rep, jobs[k], &results[k]);
      if (!ok[k]) results[k].resize(0);
    });
    *runs += 4 * static_cast<int>(jobs.size());
    for (size_t k = 0; k < jobs.size(); ++k)
      if (!ok[k]) {
        for (const std::unique_ptr<SceneReplica>& r : replicas_)
          if (r && !r->error.message.empty()) return Fail(error, r->error.message);
        return Fail(error, "a run of the step in Inject mode failed");
      }
    return true;
  }

 private:
  SceneReplica& Replica() {
    std::unique_ptr<SceneReplica>& r = replicas_.local();
    if (!r) r = std::make_unique<SceneReplica>(scene_, tape_, false);
    return *r;
  }

  // One run on a replica: y = [ρ_0 … ρ_{s−1}, S_{n+1}].
  bool Run(SceneReplica& rep, const Moves& moves, Eigen::VectorXd* y) const {
    Scene& sc = rep.scene;
    sc.Restore(before_);
    Eigen::VectorXd S = S0_;
    for (int st = 0; st < s_; ++st) rep.tape.stages[st].inject.setZero(nd_);
    std::vector<std::pair<int, double>> changed;  // parameter, nominal value
    bool valid = true;
    for (const auto& [k, v] : moves) {
      if (k < ns_) {
        S[k] += v;
      } else if (k < zSize_) {
        rep.tape.stages[(k - ns_) / nd_].inject[(k - ns_) % nd_] += v;
      } else if (valid) {
        const SceneParameter& p = model_[k - zSize_];
        changed.emplace_back(k - zSize_, ParameterValue(sc, p));
        valid = SetParameterValue(&sc, p, changed.back().second + v, &rep.error);
      }
    }
    sc.UnpackState(S);
    bool stepped = false;
    if (valid) {
      TapeRecorder inject(&rep.tape, TapeRecorder::Mode::Inject);
      stepped = sc.Step(dt_, nullptr, &rep.error, &inject);
    }
    for (const auto& [p, value] : changed) SetParameterValue(&sc, model_[p], value, nullptr);
    if (!stepped) return false;
    y->resize(m_);
    for (int st = 0; st < s_; ++st) y->segment(st * nd_, nd_) = rep.tape.stages[st].residual;
    y->tail(ns_) = sc.PackState();
    return true;
  }

  // (4 D(η/2) − D(η))/3 with D(η) = (y(+η) − y(−η))/(2η), times η (divided by each row's η later).
  bool Richardson(SceneReplica& rep, const Moves& moves, Eigen::VectorXd* e) const {
    Eigen::VectorXd plus, minus, full;
    Moves scaled = moves;
    for (double f : {1.0, 0.5}) {
      for (size_t k = 0; k < moves.size(); ++k) scaled[k].second = f * moves[k].second;
      if (!Run(rep, scaled, &plus)) return false;
      for (auto& mv : scaled) mv.second = -mv.second;
      if (!Run(rep, scaled, &minus)) return false;
      if (f == 1.0)
        full = plus - minus;
      else
        *e = (4.0 * (plus - minus) - 0.5 * full) / 3.0;
    }
    return true;
  }

  const Scene& scene_;
  const StepTape& tape_;
  const Scene::Snapshot& before_;
  const Eigen::VectorXd& S0_;
  const std::vector<SceneParameter>& model_;
  double dt_;
  int s_, nd_, ns_, zSize_, m_;
  tbb::enumerable_thread_specific<std::unique_ptr<SceneReplica>> replicas_;
};

}  // namespace

bool StepLinearizer::Linearize(Scene* scenePtr, double dt,
                               const std::vector<SceneParameter>& parameters, StepReport* report,
                               Error* error) {
  Scene& scene = *scenePtr;
  std::vector<SceneParameter> model;
  for (size_t j = 0; j < parameters.size(); ++j) {
    if (parameters[j].IsInitialState()) continue;
    if (!CheckDifferentiable(scene, parameters[j], static_cast<int>(j), error)) return false;
    model.push_back(parameters[j]);
  }
  const Scene::Snapshot before = scene.Save();
  const Eigen::VectorXd S0 = scene.PackState();
  if (!StepAndRecord(&scene, dt, &tape_, report, error)) return false;
  const StepSizes z = SizesOf(scene, tape_, S0, model);
  const int nd = z.nd, ns = z.ns, P = z.P, zSize = z.zSize, m = z.m;
  stateSize_ = ns;
  numDofs_ = nd;
  parameters_ = P;
  runs_ = 0;
  unattributed_ = 0.0;

  MoverLayout layout = LayOutMovers(scene, tape_, model, S0, dt);
  const double h = layout.h;
  std::vector<Mover>& movers = layout.movers;
  const std::vector<int>& rowUnit = layout.rowUnit;
  const std::vector<std::vector<int>>& members = layout.members;
  const std::vector<int>& aloneParameters = layout.aloneParameters;
  const std::vector<double>& parameterStep = layout.parameterStep;
  const int U = static_cast<int>(movers.size());
  colors_ = static_cast<int>(members.size());
  using Moves = InjectRuns::Moves;
  InjectRuns runs(scene, tape_, before, S0, model, dt);
  std::vector<Eigen::VectorXd> results;
  auto runJobs = [&](const std::vector<Moves>& jobs) -> bool {
    return runs.RunJobs(jobs, &results, &runs_, error);
  };

  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<int> owner(U, -1);
  bool good = true;
  // Per group: column or parameter slot j of every mover moved at once; each changed row is
  // attributed to the mover that reaches it.
  for (const std::vector<int>& group : members) {
    if (!good) break;
    size_t locals = 0, slots = 0;
    for (int u : group) {
      locals = std::max(locals, movers[u].directions.size());
      slots = std::max(slots, movers[u].parameters.size());
      for (int w : movers[u].reach) owner[w] = u;
    }
    const bool alone = group.size() == 1 && movers[group[0]].alone;
    auto direction = [&](int u, size_t j, bool parameters) -> const Direction* {
      const std::vector<Direction>& list = parameters ? movers[u].parameters : movers[u].directions;
      return j < list.size() ? &list[j] : nullptr;
    };
    std::vector<Moves> jobs;
    std::vector<std::pair<size_t, bool>> slot;  // (j, parameters) per job
    for (bool parameters : {false, true})
      for (size_t j = 0; j < (parameters ? slots : locals); ++j) {
        Moves moves;
        for (int u : group)
          if (const Direction* d = direction(u, j, parameters))
            for (const auto& [z, w] : d->move) moves.emplace_back(z, w * d->step);
        if (moves.empty()) continue;
        jobs.push_back(std::move(moves));
        slot.emplace_back(j, parameters);
      }
    good = runJobs(jobs);
    for (size_t k = 0; good && k < jobs.size(); ++k) {
      const auto [j, parameters] = slot[k];
      const Eigen::VectorXd& e = results[k];
      for (int r = 0; r < m; ++r) {
        if (e[r] == 0.0) continue;
        const int u = alone ? group[0] : owner[rowUnit[r]];
        const Direction* d = u < 0 ? nullptr : direction(u, j, parameters);
        if (!d) {
          unattributed_ = std::max(unattributed_, std::abs(e[r]) / h);
          continue;
        }
        for (const auto& [z, w] : d->spread) triplets.emplace_back(r, z, w * e[r] / d->step);
      }
    }
    for (int u : group)
      for (int w : movers[u].reach) owner[w] = -1;
  }
  if (good) {
    std::vector<Moves> jobs;
    for (int p : aloneParameters) jobs.push_back({{zSize + p, parameterStep[p]}});
    good = runJobs(jobs);
    for (size_t k = 0; good && k < jobs.size(); ++k) {
      const int p = aloneParameters[k];
      for (int r = 0; r < m; ++r)
        if (results[k][r] != 0.0)
          triplets.emplace_back(r, zSize + p, results[k][r] / parameterStep[p]);
    }
  }
  if (!good) return false;
  partials_.resize(m, zSize + P);
  partials_.setFromTriplets(triplets.begin(), triplets.end());
  return true;
}

Eigen::MatrixXd StepLinearizer::Tangent(const Eigen::MatrixXd& dS, const Eigen::MatrixXd& dTheta) {
  const int s = tape_.used, nd = numDofs_, ns = stateSize_;
  Eigen::MatrixXd out(ns, dS.cols());
  Eigen::VectorXd x(partials_.cols());
  for (Eigen::Index c = 0; c < dS.cols(); ++c) {
    x.setZero();
    x.head(ns) = dS.col(c);
    if (parameters_ > 0) x.tail(parameters_) = dTheta.col(c);
    for (int i = 0; i < s && nd > 0; ++i) {
      const Eigen::VectorXd rho = (partials_ * x).segment(i * nd, nd);
      x.segment(ns + i * nd, nd) = -tape_.stages[i].lu->Solve(rho);
    }
    out.col(c) = (partials_ * x).tail(ns);
  }
  return out;
}

void StepLinearizer::Adjoint(const Eigen::VectorXd& lambda, Eigen::VectorXd* lambdaPrevious,
                             Eigen::VectorXd* parameterGradient) {
  const int s = tape_.used, nd = numDofs_, ns = stateSize_;
  Eigen::VectorXd y = Eigen::VectorXd::Zero(partials_.rows());
  y.tail(ns) = lambda;
  for (int i = s - 1; i >= 0 && nd > 0; --i) {
    const Eigen::VectorXd w = partials_.middleCols(ns + i * nd, nd).transpose() * y;
    y.segment(i * nd, nd) = -tape_.stages[i].lu->SolveTransposed(w);
  }
  *lambdaPrevious = partials_.leftCols(ns).transpose() * y;
  *parameterGradient = partials_.rightCols(parameters_).transpose() * y;
}

}  // namespace superdex
