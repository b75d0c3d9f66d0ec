#include "core/contact/contact_stencil.h"

namespace superdex {

void ScatterStencil(const ContactStencil& s, const int* offs, int blocks, bool potential,
                    Eigen::VectorXd* gradient, Eigen::VectorXd* dissipationResidual,
                    std::vector<Eigen::Triplet<double>>* triplets) {
  Eigen::VectorXd* dr = dissipationResidual ? dissipationResidual : gradient;
  for (int b = 0; b < blocks; ++b) {
    if (offs[b] < 0) continue;
    if (s.penaltyActive) gradient->segment<3>(offs[b]) += s.penaltyGradient.segment<3>(3 * b);
    if (s.dissipationActive) dr->segment<3>(offs[b]) += s.dissipationResidual.segment<3>(3 * b);
  }
  if (!triplets) return;
  const StencilMatrix* H =
      s.penaltyActive || (potential && s.dissipationActive) ? &s.penaltyHessian : nullptr;
  const StencilMatrix* J = !potential && s.dissipationActive ? &s.dissipationJacobian : nullptr;
  for (int bi = 0; bi < blocks; ++bi) {
    if (offs[bi] < 0) continue;
    for (int bj = 0; bj < blocks; ++bj) {
      if (offs[bj] < 0) continue;
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) {
          double v = 0.0;
          if (H) v += (*H)(3 * bi + r, 3 * bj + c);
          if (J) v += (*J)(3 * bi + r, 3 * bj + c);
          if (v != 0.0) triplets->emplace_back(offs[bi] + r, offs[bj] + c, v);
        }
    }
  }
}

}  // namespace superdex
