#include "energies/normal_penalty.h"

#include "energies/penalty_ramp.h"

namespace superdex {

PenaltyDensity NormalPenaltyDensity(double phi, const PenaltyParams& p) {
  const RampValue r = PenaltyRamp(phi, p.eps, p.delta);
  PenaltyDensity d;
  d.W = 0.5 * p.k * r.h * r.h;
  d.lambdaN = p.k * r.h * r.dh;
  d.dW = -d.lambdaN;
  d.d2W = p.k * (r.dh * r.dh + r.h * r.d2h);
  return d;
}

void AddNormalPenalty(const PenaltyDensity& density, double weight, const StencilVector& gradPhi,
                      const StencilMatrix& hessPhi, double* value, StencilVector* grad,
                      StencilMatrix* hess) {
  *value += weight * density.W;
  grad->noalias() += (weight * density.dW) * gradPhi;
  if (hess) {
    hess->noalias() += (weight * density.d2W) * gradPhi * gradPhi.transpose();
    hess->noalias() += (weight * density.dW) * hessPhi;
  }
}

}  // namespace superdex
