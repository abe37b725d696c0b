// The two-state model of trial-by-trial sensorimotor adaptation (Smith, Ghazizadeh & Shadmehr
// 2006, PLoS Biology 4(6):e179): a fast process that learns quickly and forgets quickly and a
// slow one that learns slowly and retains, each updated by the same observed error,
//   x_fast <- A_fast x_fast + B_fast e,   x_slow <- A_slow x_slow + B_slow e,
// their sum the correction applied on the next trial. One state per context the person can
// tell apart (here the cube's seen size: Howard, Wolpert & Franklin 2013 on which cues keep
// memories apart).
#pragma once

namespace handlab::studies {

struct TwoRateRates {
  double retain_fast = 0.0, learn_fast = 0.0, retain_slow = 0.0, learn_slow = 0.0;
};

struct TwoRateState {
  double fast = 0.0, slow = 0.0;
  double correction() const { return fast + slow; }
};

// The state after a trial whose error was `error` (the units of the correction).
TwoRateState adapt(const TwoRateState& state, const TwoRateRates& rates, double error);
// The state after a trial that gave no error signal: only forgetting.
TwoRateState forget(const TwoRateState& state, const TwoRateRates& rates);

}  // namespace handlab::studies
