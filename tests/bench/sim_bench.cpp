// The flesh alone: one backward-Euler Newton step of the study hand's tetrahedral flesh
// (linear co-rotational FEM), its coupling points tied by springs to where the bones hold
// them, so that the system has the simulator's size and conditioning.
#include <benchmark/benchmark.h>

#include "core/hand/flesh.h"
#include "core/hand/simulated_hand.h"
#include "core/sim/supernodal_ldlt.h"
#include "core/sim/thread_pool.h"
#include "tests/core/sim/reference/elastic_body.h"
#include "tests/support/hand_like_matrix.h"

namespace {

void BM_FleshStep(benchmark::State& state) {
  using namespace handlab;
  const hand::HandShape shape = hand::HandShape::with_length(0.214);
  const hand::Skeleton skeleton = hand::build_simulated_hand(shape);
  hand::FleshOptions options;
  options.resolution = int(state.range(0));
  const hand::HandFlesh flesh = hand::build_flesh(skeleton, shape, options);
  sim::ElasticBodyModel model = sim::make_elastic_body(flesh.tets, {30e3, 0.45}, 1100.0);
  // Every node of a tet that holds a coupling point is tied to its rest place.
  std::vector<Eigen::Vector3d> anchors;
  std::vector<bool> tied(flesh.tets.nodes.size(), false);
  for (const auto& c : flesh.coupling)
    for (int node : flesh.tets.tets[std::size_t(c.tet)]) tied[std::size_t(node)] = true;
  for (std::size_t i = 0; i < tied.size(); ++i)
    if (tied[i]) {
      model.springs.push_back({int(i), 50.0});
      anchors.push_back(model.rest[i]);
    }
  sim::ElasticBodySolver solver(model);
  sim::ElasticBodyState s = sim::rest_state(model);
  for (auto _ : state) benchmark::DoNotOptimize(solver.step(s, anchors).residual);
  state.counters["tets"] = double(model.tets.size());
  state.counters["nodes"] = double(model.rest.size());
}
BENCHMARK(BM_FleshStep)->Arg(1)->Arg(4)->ArgName("resolution")->Unit(benchmark::kMillisecond);

// The sparse factorisation the simulator's solves use (core/sim/supernodal_ldlt.h), on a
// matrix of the study hand's structure (flesh nodes and 16 bones): one numeric factorisation
// (on one lane, or split over two), and one solve with it.
const Eigen::SparseMatrix<double>& hand_like_system() {
  static const Eigen::SparseMatrix<double> a =
      handlab::test::hand_like_matrix(handlab::test::study_flesh(), 16, 1);
  return a;
}

// The panels analysed for the hand-like system.
void analyse(handlab::sim::SupernodalLdlt& panels) {
  const handlab::sim::SupernodalLdlt::Factor ldlt(hand_like_system());
  panels.analyze(ldlt, hand_like_system());
}

void BM_SupernodalFactorize(benchmark::State& state) {
  using namespace handlab;
  const Eigen::SparseMatrix<double>& a = hand_like_system();
  sim::SupernodalLdlt panels;
  analyse(panels);
  sim::ThreadPool pool(int(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(panels.factorize(a, &pool));
  state.counters["supernodes"] = panels.supernodes();
  state.counters["values"] = panels.value_count();
  state.counters["dofs"] = double(a.cols());
}
BENCHMARK(BM_SupernodalFactorize)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("workers")
    ->Unit(benchmark::kMillisecond);

void BM_SupernodalSolve(benchmark::State& state) {
  using namespace handlab;
  const Eigen::SparseMatrix<double>& a = hand_like_system();
  sim::SupernodalLdlt panels;
  analyse(panels);
  panels.factorize(a);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(a.cols(), -1.0, 1.0);
  Eigen::VectorXd x;
  for (auto _ : state) {
    x = b;
    panels.solve_in_place(x);
    benchmark::DoNotOptimize(x.data());
  }
}
BENCHMARK(BM_SupernodalSolve)->Unit(benchmark::kMicrosecond);

}  // namespace
