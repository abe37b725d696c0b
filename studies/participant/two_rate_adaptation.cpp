#include "studies/participant/two_rate_adaptation.h"

namespace handlab::studies {

TwoRateState adapt(const TwoRateState& s, const TwoRateRates& r, double error) {
  return {r.retain_fast * s.fast + r.learn_fast * error,
          r.retain_slow * s.slow + r.learn_slow * error};
}

TwoRateState forget(const TwoRateState& s, const TwoRateRates& r) {
  return adapt(s, r, 0.0);
}

}  // namespace handlab::studies
