#include "studies/analysis/grasp_tally.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace handlab::studies {
namespace {

std::string cube_group(double size) {
  const double cm = std::round(size * 1e3) / 10.0;
  char text[32];
  std::snprintf(text, sizeof text, "%g cm", cm);
  return text;
}

int offset_bin(const GraspContact& g) {
  const double share = std::hypot(g.pinch_offset.x(), g.pinch_offset.z()) / g.cube_size;
  int bin = 0;
  for (double edge : kPinchOffsetEdges) bin += share >= edge ? 1 : 0;
  return bin;
}

void count(GraspCount& c, bool was_lost) {
  ++c.grasps;
  c.lost += was_lost ? 1 : 0;
}

void add(GraspTally& t, const GraspContact& g) {
  const bool was_lost = lost(g.outcome);
  ++t.grasps;
  t.placed += g.outcome == GraspOutcome::kPlaced ? 1 : 0;
  t.dropped += g.outcome == GraspOutcome::kDropped ? 1 : 0;
  t.landed += g.outcome == GraspOutcome::kLanded ? 1 : 0;
  t.caught_again += g.outcome == GraspOutcome::kCaughtAgain ? 1 : 0;
  t.unfinished += g.outcome == GraspOutcome::kUnfinished ? 1 : 0;
  count(t.by_thumb[std::size_t(g.thumb)], was_lost);
  count(t.by_index[std::size_t(g.index)], was_lost);
  count(t.by_offset[std::size_t(offset_bin(g))], was_lost);
  if (g.closing) (was_lost ? t.lost_closings : t.kept_closings).push_back(*g.closing);
}

void write_spread(util::JsonWriter& w, const char* key, const std::vector<double>& values,
                  double unit) {
  const FactorSpread s = spread_of(values, unit);
  w.key(key).begin_object().field("n", s.n);
  if (s.n > 0) w.field("p10", s.p10).field("median", s.median).field("p90", s.p90);
  w.end_object();
}

void write_spreads(util::JsonWriter& w, const std::vector<LoggedClosing>& closings) {
  w.begin_object();
  for (const LoggedFactor& f : logged_factors()) {
    const FactorSpread s = factor_spread(closings, f);
    w.key(f.name).begin_object().field("unit", f.unit).field("n", s.n);
    if (s.n > 0) w.field("p10", s.p10).field("median", s.median).field("p90", s.p90);
    w.end_object();
  }
  w.end_object();
}

void write_counts(util::JsonWriter& w, const std::array<GraspCount, 3>& by_part) {
  w.begin_object();
  for (PhalanxPart part : {PhalanxPart::kBase, PhalanxPart::kPad, PhalanxPart::kTip}) {
    const GraspCount& c = by_part[std::size_t(part)];
    w.key(phalanx_part_name(part)).begin_object();
    w.field("grasps", c.grasps).field("lost", c.lost).end_object();
  }
  w.end_object();
}

}  // namespace

std::vector<GraspTally> tally_grasps(const std::vector<TrialGrasps>& trials,
                                     GraspGrouping grouping) {
  std::vector<GraspTally> tallies;
  for (const TrialGrasps& trial : trials) {
    const std::string group =
        grouping == GraspGrouping::kCondition ? trial.condition : cube_group(trial.cube_size);
    auto it = std::find_if(tallies.begin(), tallies.end(),
                           [&](const GraspTally& t) { return t.group == group; });
    if (it == tallies.end()) {
      GraspTally tally;
      tally.group = group;
      tally.cube_size = trial.cube_size;
      tallies.push_back(std::move(tally));
      it = tallies.end() - 1;
    }
    ++it->trials;
    it->jitter_root_rms.push_back(trial.jitter_root_rms);
    it->jitter_angle_rms.push_back(trial.jitter_angle_rms);
    for (const GraspContact& g : trial.grasps) add(*it, g);
  }
  return tallies;
}

void write_grasps_json(util::JsonWriter& w, const std::vector<TrialGrasps>& trials,
                       const std::vector<GraspTally>& tallies) {
  w.begin_object().field("trials", trials.size()).key("groups").begin_array();
  for (const GraspTally& t : tallies) {
    w.begin_object().field("group", t.group).field("cube_size_m", t.cube_size);
    w.field("trials", t.trials).field("grasps", t.grasps).field("placed", t.placed);
    w.field("dropped", t.dropped).field("landed", t.landed);
    w.field("caught_again", t.caught_again).field("unfinished", t.unfinished);
    w.field("lost", t.lost());
    w.key("by_thumb");
    write_counts(w, t.by_thumb);
    w.key("by_index");
    write_counts(w, t.by_index);
    w.key("by_pinch_offset").begin_array();
    for (std::size_t bin = 0; bin < t.by_offset.size(); ++bin) {
      w.begin_object();
      w.key("from_share").value(bin == 0 ? 0.0 : kPinchOffsetEdges[bin - 1]);
      w.key("to_share");
      if (bin < kPinchOffsetEdges.size())
        w.value(kPinchOffsetEdges[bin]);
      else
        w.null();
      w.field("grasps", t.by_offset[bin].grasps).field("lost", t.by_offset[bin].lost);
      w.end_object();
    }
    w.end_array().key("jitter").begin_object();
    write_spread(w, "root_rms_mm", t.jitter_root_rms, 1e-3);
    write_spread(w, "angle_rms_deg", t.jitter_angle_rms, M_PI / 180);
    w.end_object().key("closings").begin_object().key("kept");
    write_spreads(w, t.kept_closings);
    w.key("lost");
    write_spreads(w, t.lost_closings);
    w.end_object().end_object();
  }
  w.end_array().key("grasps").begin_array();
  for (const TrialGrasps& trial : trials)
    for (const GraspContact& g : trial.grasps) {
      w.begin_object().field("participant", trial.participant);
      w.field("trial", trial.position + 1).field("attempt", trial.attempt);
      w.field("condition", trial.condition).field("cube_size_m", g.cube_size);
      w.field("time_s", g.time).field("held_s", g.held);
      w.field("outcome", grasp_outcome_name(g.outcome));
      w.field("thumb", phalanx_part_name(g.thumb)).field("index", phalanx_part_name(g.index));
      w.key("pinch_offset_m").begin_array();
      for (int axis = 0; axis < 3; ++axis) w.value(g.pinch_offset[axis]);
      w.end_array();
      if (g.closing) {
        w.key("closing").begin_object();
        for (const LoggedFactor& f : logged_factors()) {
          const double v = (*g.closing).*(f.field);
          w.key(f.name);
          if (std::isnan(v))
            w.null();
          else
            w.value(v / f.scale);
        }
        w.end_object();
      }
      w.end_object();
    }
  w.end_array().end_object();
}

}  // namespace handlab::studies
