#include "optim/forcing_term.h"

#include <algorithm>
#include <cmath>

namespace superdex {

double ForcingTerm::Next(double norm) {
  double eta = lastNorm_ < 0.0 && tightStart_ ? floor_ : kEtaMax;
  if (lastNorm_ > 0.0 && std::isfinite(lastNorm_) && std::isfinite(norm)) {
    const double ratio = norm / lastNorm_;
    eta = std::min(kEtaMax, kGamma * ratio * ratio);
  }
  lastNorm_ = norm;
  return std::max(eta, floor_);
}

}  // namespace superdex
