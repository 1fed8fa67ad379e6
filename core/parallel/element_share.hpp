#pragma once
/// @file How the ranks of a run on several MPI ranks share the element loop (docs/many_machines.md, "One run
/// on several MPI ranks"): the nodes are partitioned among the ranks, the same partition by which PETSc owns
/// the matrix rows; each rank computes every element with a node of its own, so that its own rows of the
/// residual and the matrix are whole, the same sums in the same order as on one process. The residual's
/// other rows come from their owners (a sum over the ranks to which only the owner adds); the matrix's other
/// rows are left partial, since each rank passes PETSc only its own. A process of its own computes every
/// element, as it always did.

#include <array>
#include <functional>
#include <vector>

namespace stoss::parallel {

/// This rank's part of the nodes and elements, and the sum over the ranks.
struct ElementShare {
  int rank = 0;
  int size = 1;
  /// Sums `count` doubles over every rank in place, the same bits on every rank (a reduction to rank 0 and a
  /// broadcast: an all-reduce may associate differently on different ranks, and ranks that differ in a bit
  /// could take different Newton decisions).
  std::function<void(double* values, long count)> sum;
  std::vector<int> node_part;  ///< the rank that owns each node (its position rows)
  std::vector<int> elements;   ///< the elements with a node this rank owns, ascending
  bool shared() const { return size > 1 && sum != nullptr; }
  bool owns(int node) const { return node_part[node] == rank; }
  /// Per position row (3 per node): whether this rank owns it.
  std::vector<char> own_rows() const;
};

/// Node indices of each hex8 (mesh::Mesh::hex8).
using Elements = std::vector<std::array<int, 8>>;

/// The share of rank `rank` of `size` for the nodes' owners `node_part` of the mesh's `hex8`: its elements
/// are those with a node it owns.
ElementShare share_of(const Elements& hex8, std::vector<int> node_part, int rank, int size,
                      std::function<void(double*, long)> sum);

/// The graph of `nodes` nodes of the mesh's `hex8` in CSR (`offsets` of nodes + 1, `neighbours`), two nodes
/// adjacent when an element holds both, each node's neighbours ascending: the graph the nodes are
/// partitioned on.
void node_graph(const Elements& hex8, int nodes, std::vector<int>& offsets, std::vector<int>& neighbours);

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
