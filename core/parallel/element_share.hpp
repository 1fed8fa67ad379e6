#pragma once
/// @file How the ranks of a run on several MPI ranks share the element loop (docs/many_machines.md, "One run
/// on several MPI ranks"): each rank computes a contiguous range of the elements, and the ranks' sums are
/// summed over the ranks so that every rank holds the whole residual and matrix. A process of its own
/// computes every element, as it always did.

#include <functional>
#include <utility>

namespace stoss::parallel {

/// This rank's part of the elements and the sum over the ranks.
struct ElementShare {
  int rank = 0;
  int size = 1;
  /// Sums `count` doubles over every rank in place, the same bits on every rank (a reduction to rank 0 and a
  /// broadcast: an all-reduce may associate differently on different ranks, and ranks that differ in a bit
  /// could take different Newton decisions).
  std::function<void(double* values, long count)> sum;
  bool shared() const { return size > 1 && sum != nullptr; }
  /// [first, last) of n elements for this rank: n / size each, the first n % size ranks one more.
  std::pair<int, int> range(int n) const;
};

/// The share the element loops of this process use; {0, 1, none} until set.
const ElementShare& element_share();
/// Set once the ranks of a launch have met (core/run/ranks.cpp); {} to compute every element again.
void set_element_share(ElementShare share);

/// `value` summed over the ranks of the share (`value` itself on a process of its own): the run's peak
/// memory is that of all its ranks. Every rank must call it at the same point of the run.
double total_over_ranks(double value);
/// True on every rank when `asked` is true on any: a cancel that reached one rank first stops every rank at
/// the same step. Every rank must call it at the same point of the run.
bool on_any_rank(bool asked);

}  // namespace stoss::parallel
