// The state hooks of LagrangeContactTerm (checkpoint and resume): what a converged step leaves for the
// next one is the list of active elements; the rest of an element is recomputed by prepare_step.
#include <string>

#include "core/contact/lagrange/lagrange_term.hpp"

namespace stoss::contact {
namespace {

template <int N, class Vector>
void append(std::vector<double>& out, const Vector& v) {
  for (int i = 0; i < N; ++i) out.push_back(v[i]);
}

template <int N, class Vector>
void read(const std::vector<double>& in, size_t k, Vector& v) {
  for (int i = 0; i < N; ++i) v[i] = in[N * k + i];
}

}  // namespace

time::TermState LagrangeContactTerm::save_state() const {
  time::TermState s;
  auto& slave = s.integers["slave"];
  auto& face = s.integers["face"];
  auto& f3 = s.reals["f3"];
  auto& d = s.reals["d"];
  auto& xi = s.reals["xi"];
  auto& lambda = s.reals["lambda"];
  for (const ContactElement& e : committed_) {
    slave.push_back(e.slave);
    face.push_back(e.face);
    f3.push_back(e.f3);
    append<3>(d, e.d);
    append<2>(xi, e.xi);
    append<6>(lambda, e.lambda);
  }
  auto& armed = s.integers["armed"];  // §4.6.2: nodes whose located event the last step ended at
  for (size_t i = 0; i < armed_.size(); ++i)
    if (armed_[i]) armed.push_back(static_cast<std::int64_t>(i));
  s.reals["previous_step"] = {previous_step_};
  return s;
}

void LagrangeContactTerm::restore_state(const time::TermState& state, const Eigen::VectorXd& x,
                                        const Eigen::VectorXd& v) {
  const auto slaves = state.integers.find("slave");
  const size_t n = slaves == state.integers.end() ? 0 : slaves->second.size();
  const auto& slave = state.integer("slave", n);
  const auto& face = state.integer("face", n);
  const auto& f3 = state.real("f3", n);
  const auto& d = state.real("d", 3 * n);
  const auto& xi = state.real("xi", 2 * n);
  const auto& lambda = state.real("lambda", 6 * n);
  std::vector<ContactElement> elements(n);
  for (size_t k = 0; k < n; ++k) {
    ContactElement& e = elements[k];
    if (slave[k] < 0 || slave[k] >= static_cast<std::int64_t>(surfaces_.slave_nodes.size()) || face[k] < 0 ||
        face[k] >= static_cast<std::int64_t>(surfaces_.faces.size()))
      throw std::invalid_argument("term state of " + name() + ": element " + std::to_string(k) +
                                  " names a slave node or face the pair does not have");
    e.slave = static_cast<int>(slave[k]);
    e.face = static_cast<int>(face[k]);
    e.f3 = f3[k];
    read<3>(d, k, e.d);
    read<2>(xi, k, e.xi);
    read<6>(lambda, k, e.lambda);
    e.d_n = e.d;
    e.xi_n = e.xi;
  }
  // Replay the end of the step that left this state: a subclass rebuilds what it keeps of it (HHT's
  // λ_n N_s(x_n)) from the elements and z = [x; their auxiliaries]. read_auxiliaries may re-project ξ and
  // d, so the elements are set to the saved ones afterwards.
  elements_ = elements;
  set_auxiliary_offset(static_cast<int>(x.size()));
  Eigen::VectorXd z = Eigen::VectorXd::Zero(x.size() + auxiliary_count());
  z.head(x.size()) = x;
  for (size_t k = 0; k < elements_.size(); ++k)
    write_auxiliaries(elements_[k], x, element_offset(static_cast<int>(k)), z);
  const time::StepContext step{x, v, 0.0};
  in_step_ = true;
  end_step(step, z);
  elements_ = std::move(elements);
  committed_ = elements_;
  in_step_ = false;
  std::fill(armed_.begin(), armed_.end(), 0);
  if (const auto armed = state.integers.find("armed"); armed != state.integers.end())
    for (std::int64_t i : armed->second) {
      if (i < 0 || i >= static_cast<std::int64_t>(armed_.size()))
        throw std::invalid_argument("term state of " + name() + ": armed slave " + std::to_string(i) +
                                    " is not a slave node of the pair");
      armed_[i] = 1;
    }
  previous_step_ = state.reals.count("previous_step") ? state.real("previous_step", 1)[0] : 0.0;
  reindex();
  ++generation_;
}

}  // namespace stoss::contact
