#include "core/dynamics/integrators.h"

#include <cmath>

namespace superdex {
namespace {

DirkTableau Make(int s, std::initializer_list<double> a, std::initializer_list<double> b,
                 int order) {
  DirkTableau t;
  t.stages = s;
  t.order = order;
  auto ia = a.begin();
  for (int i = 0; i < s; ++i)
    for (int j = 0; j < s; ++j) t.a[i][j] = *ia++;
  auto ib = b.begin();
  for (int i = 0; i < s; ++i) t.b[i] = *ib++;
  t.stifflyAccurate = true;
  for (int i = 0; i < s; ++i) t.stifflyAccurate &= std::abs(t.b[i] - t.a[s - 1][i]) < 1e-15;
  return t;
}

const DirkTableau& BackwardEulerTableau() {
  static const DirkTableau t = Make(1, {1.0}, {1.0}, 1);
  return t;
}

const DirkTableau& Dirk22() {
  // L-stable, stiffly accurate, γ = 1 − √2/2.
  static const DirkTableau t = [] {
    const double g = 1.0 - std::sqrt(2.0) / 2.0;
    return Make(2, {g, 0.0, 1.0 - g, g}, {1.0 - g, g}, 2);
  }();
  return t;
}

const DirkTableau& Dirk23() {
  // A-stable, order 3, γ = 1/2 + 1/(2√3).
  static const DirkTableau t = [] {
    const double g = 0.5 + 0.5 / std::sqrt(3.0);
    return Make(2, {g, 0.0, 1.0 - 2.0 * g, g}, {0.5, 0.5}, 3);
  }();
  return t;
}

const DirkTableau& Dirk33() {
  // Alexander's L-stable, stiffly accurate 3-stage method of order 3; γ is the root of
  // x³ − 3x² + 3x/2 − 1/6 = 0 in (1/6, 1/2).
  static const DirkTableau t = [] {
    const double g = 0.435866521508458999416019;
    const double b1 = -(6.0 * g * g - 16.0 * g + 1.0) / 4.0;
    const double b2 = (6.0 * g * g - 20.0 * g + 5.0) / 4.0;
    return Make(3, {g, 0.0, 0.0, (1.0 - g) / 2.0, g, 0.0, b1, b2, g}, {b1, b2, g}, 3);
  }();
  return t;
}

const DirkTableau& SymplecticDirk12() {
  static const DirkTableau t = Make(1, {0.5}, {1.0}, 2);  // implicit midpoint
  return t;
}

const DirkTableau& SymplecticDirk22() {
  // Two implicit-midpoint half steps: symplectic, order 2.
  static const DirkTableau t = Make(2, {0.25, 0.0, 0.5, 0.25}, {0.5, 0.5}, 2);
  return t;
}

}  // namespace

bool IsMultistep(IntegrationMethod m) {
  return m == IntegrationMethod::BDF2 || m == IntegrationMethod::BDF3;
}

int BdfSteps(IntegrationMethod m) {
  return m == IntegrationMethod::BDF3 ? 3 : m == IntegrationMethod::BDF2 ? 2 : 1;
}

const DirkTableau& TableauOf(IntegrationMethod m) {
  switch (m) {
    case IntegrationMethod::DIRK22: return Dirk22();
    case IntegrationMethod::DIRK23: return Dirk23();
    case IntegrationMethod::DIRK33: return Dirk33();
    case IntegrationMethod::SymplecticDIRK12: return SymplecticDirk12();
    case IntegrationMethod::SymplecticDIRK22: return SymplecticDirk22();
    default: return BackwardEulerTableau();
  }
}

int DesignOrder(IntegrationMethod m) {
  switch (m) {
    case IntegrationMethod::BackwardEuler: return 1;
    case IntegrationMethod::BDF2: return 2;
    case IntegrationMethod::BDF3: return 3;
    default: return TableauOf(m).order;
  }
}

double BdfCoefficients(const std::vector<double>& times, std::vector<double>* weights) {
  const int k = static_cast<int>(times.size()) - 1;
  const double t0 = times[0];
  double l0 = 0.0;  // ℓ'_0(τ_0) = Σ_{m≠0} 1/(τ_0 − τ_m)
  for (int m = 1; m <= k; ++m) l0 += 1.0 / (t0 - times[m]);
  const double dt = 1.0 / l0;
  weights->assign(k, 0.0);
  for (int j = 1; j <= k; ++j) {
    // ℓ'_j(τ_0) = Π_{m≠j,0}(τ_0 − τ_m) / Π_{m≠j}(τ_j − τ_m)
    double num = 1.0, den = 1.0;
    for (int m = 0; m <= k; ++m) {
      if (m == j) continue;
      if (m != 0) num *= t0 - times[m];
      den *= times[j] - times[m];
    }
    (*weights)[j - 1] = -dt * num / den;
  }
  return dt;
}

}  // namespace superdex
