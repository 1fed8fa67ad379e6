// Steps cut at located contact events (docs/theory.md §4.6.2): a term that asks for a cut makes the
// integrator solve the step again, shortened to it, and step reduction then solves the rest, so the full step
// still ends at t_n + h; the cuts per step are bounded (Integrator::max_event_cuts), after which the term is
// told it may no longer cut.
#include <gtest/gtest.h>

#include "core/fem/assembly.hpp"
#include "core/mesh/generators.hpp"
#include "core/time/integrator.hpp"
#include "core/time/step_reduction.hpp"

namespace stoss::time {
namespace {

/// A term without forces with one event at time `event`: it asks to cut every step that passes it.
class EventTerm : public Term {
 public:
  explicit EventTerm(double event, double always = 1) : event_(event), always_(always) {}
  std::string name() const override { return "event"; }
  void register_blocks(solve::BlockPattern&) override {}
  void add(const StepContext&, const Eigen::VectorXd&, Eigen::VectorXd&,
           solve::BlockPattern*) const override {}
  void prepare_step(const StepContext& step) override {
    cut_ = 1;
    may_cut.push_back(step.may_cut);
  }
  bool update_active_set(const StepContext& step, const Eigen::VectorXd&) override {
    if (!step.may_cut) return false;
    if (always_ < 1)
      cut_ = always_;
    else if (event_ > t_ + 1e-12 && event_ < t_ + step.h - 1e-12)
      cut_ = (event_ - t_) / step.h;
    return false;
  }
  double requested_cut() const override { return cut_; }
  void end_step(const StepContext& step, const Eigen::VectorXd&) override {
    t_ += step.h;
    steps.push_back(step.h);
  }
  std::vector<double> steps;  ///< h of each converged integrator step
  std::vector<bool> may_cut;  ///< StepContext::may_cut of each solve

 private:
  double event_, always_, t_ = 0, cut_ = 1;
};

struct FreeCube {
  mesh::Mesh mesh;
  solve::SparseMatrix M;
  State s;
  FreeCube() {
    mesh.add_body("cube", mesh::box({0, 0, 0}, {1, 1, 1}, {1, 1, 1}));
    M = fem::assemble_mass(mesh, fem::precompute_mesh(mesh), {1.0});
    const Eigen::VectorXd x = mesh.reference_positions();
    s = State{x, Eigen::VectorXd::Constant(x.size(), 0.5), Eigen::VectorXd::Zero(x.size())};
  }
  Integrator integrator(Term& term) const {
    return Integrator(M, {&term}, std::vector<char>(s.x.size(), 0),
                      make_scheme(model::TimeSpec{model::Scheme::energy_momentum}), {}, 1.0, 1.0);
  }
};

TEST(EventCuts, AStepEndsAtTheLocatedEventAndStepReductionSolvesTheRest) {
  FreeCube c;
  EventTerm term(0.0037);
  Integrator integrator = c.integrator(term);
  const Eigen::VectorXd x0 = c.s.x;
  const ReducedStep r = step_with_reduction(integrator, c.s, 0.01, 4, {});
  ASSERT_TRUE(r.converged);
  EXPECT_EQ(r.substeps, 1) << "no reduction";
  EXPECT_EQ(r.event_substeps, 1);
  ASSERT_EQ(term.steps.size(), 2u);
  EXPECT_NEAR(term.steps[0], 0.0037, 1e-15);
  EXPECT_NEAR(term.steps[1], 0.0063, 1e-15);
  EXPECT_DOUBLE_EQ(c.s.t, 0.01);
  EXPECT_EQ(c.s.step, 1);
  EXPECT_NEAR((c.s.x - x0 - 0.01 * c.s.v).cwiseAbs().maxCoeff(), 0, 1e-14)
      << "free flight over the whole step";
}

TEST(EventCuts, CutsPerStepAreBoundedAndTheLastSolveMayNotCut) {
  FreeCube c;
  EventTerm term(0, 0.5);  // asks for half of every step
  Integrator integrator = c.integrator(term);
  ASSERT_TRUE(integrator.step(c.s, 0.01).converged);
  const int cuts = Integrator::max_event_cuts;
  EXPECT_DOUBLE_EQ(integrator.advanced(), 0.01 / (1 << cuts));
  ASSERT_EQ(term.may_cut.size(), static_cast<size_t>(cuts + 1));
  for (int k = 0; k < cuts; ++k) EXPECT_TRUE(term.may_cut[k]) << k;
  EXPECT_FALSE(term.may_cut.back());
  EXPECT_DOUBLE_EQ(c.s.t, 0.01 / (1 << cuts));
}

}  // namespace
}  // namespace stoss::time
