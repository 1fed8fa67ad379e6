#pragma once
/// @file Model: what a validated scene becomes. Plain data, immutable during a run.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/mesh/mesh.hpp"

namespace stoss::model {

/// `equilibrium` is `time.scheme: "static"` (docs/theory.md §5b.6): load steps without inertia.
enum class Scheme { midpoint, energy_momentum, hht, generalized_alpha, equilibrium };
/// Every dynamic scheme, in the order the docs list them (a study compares these).
inline constexpr Scheme all_schemes[] = {Scheme::energy_momentum, Scheme::midpoint, Scheme::hht,
                                         Scheme::generalized_alpha};
/// Every scheme a scene may name: the dynamic ones, then static load steps.
inline constexpr Scheme scene_schemes[] = {Scheme::energy_momentum, Scheme::midpoint, Scheme::hht,
                                           Scheme::generalized_alpha, Scheme::equilibrium};
/// The scene's name: energy_momentum, midpoint, hht, generalized_alpha, static.
std::string to_string(Scheme s);
/// The scheme named `name` (one of scene_schemes), or nullopt.
std::optional<Scheme> scheme_from_string(std::string_view name);

/// St. Venant–Kirchhoff parameters (docs/theory.md (1.4)–(1.5)).
struct Material {
  std::string model = "saint_venant_kirchhoff";
  double youngs_modulus = 0;
  double poisson_ratio = 0;
  double density = 0;
};

struct BodySpec {
  std::string name;
  Material material;
  Eigen::Vector3d initial_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d initial_angular_velocity = Eigen::Vector3d::Zero();
  /// Point the angular velocity turns about; unset means the body's centre of mass.
  std::optional<Eigen::Vector3d> center;
};

/// Dirichlet condition: the nodes of a surface keep their initial position in the fixed directions.
struct Boundary {
  std::string surface;  ///< "body/surface"
  std::array<bool, 3> fix{true, true, true};
  /// u of x = X + a(t)·u on the held directions (docs/scene.md "boundary"); 0: a support at rest
  Eigen::Vector3d displacement = Eigen::Vector3d::Zero();
  std::vector<std::array<double, 2>> amplitude;  ///< a(t) as [[t, factor], …]; empty: the factor is 1
  bool moves() const { return displacement != Eigen::Vector3d::Zero(); }
};

/// An external load on a surface (scene `loads[i]`, docs/scene.md; docs/theory.md §5b): a follower
/// pressure or a dead traction per unit reference area, scaled by a piecewise-linear amplitude (5b.1).
struct Load {
  enum class Kind { pressure, traction };
  std::string surface;  ///< "body/surface"
  Kind kind = Kind::pressure;
  double pressure = 0;  ///< positive pushes into the body
  Eigen::Vector3d traction = Eigen::Vector3d::Zero();
  std::vector<std::array<double, 2>> amplitude;  ///< [[t, factor], …]; empty: the factor is 1
};

enum class Enforcement { lagrange, penalty };
/// Energy treatment of Lagrange contact at impacts (docs/theory.md §4.5). `located` (opt-in, §4.6): each
/// slave node's activation and release end a sub-step at their located time, with both contact surfaces
/// massless under the midpoint-type schemes; energy exact, second order where h resolves the surface layer
/// (measured orders: §4.6.4).
enum class ImpactMode { persist, exact, velocity_correction, located };
enum class NormalTraction { discrete_derivative, midpoint };
/// Gap target of an active element that moves to another master face (docs/theory.md §3.4).
enum class SwitchGap {
  clamp,  ///< f_3 := min(max(g_N^new(x_n), 0), f_3^old): no frozen penetration; the step may jump in energy
  keep,  ///< f_3 := g_N^new(x_n): energy exact; the node may stay below the new face (≤ kink × ε_sw × ℓ/2)
};

/// The master surface contact sees (docs/smooth_master_surface.md §1).
enum class MasterSurface {
  faceted,  ///< the bilinear faces of the mesh (C0: kinks at every edge)
  smooth,   ///< cubic B-spline patches over each face's 4×4 neighbourhood (C1 and more)
};

/// How a pair's contact constraint is discretised (scene `contact[i].discretization`): one-pass
/// node-to-segment (docs/theory.md §3–4) or segment-based mortar with dual multipliers on the faceted master
/// (§4.7).
enum class Discretization { node_to_segment, mortar };
/// The scene's name: "node_to_segment", "mortar".
std::string to_string(Discretization d);

/// One contact pair (docs/theory.md §3–5). Slave nodes against master faces.
struct ContactPair {
  std::string slave;   ///< "body/surface"
  std::string master;  ///< "body/surface"
  Enforcement enforcement = Enforcement::lagrange;
  Discretization discretization = Discretization::node_to_segment;
  double friction = 0;  ///< Coulomb μ; > 0 makes the pair frictional (penalty)
  ImpactMode impact = ImpactMode::persist;
  double switch_hysteresis = 0.05;  ///< ε_sw of §3.4
  SwitchGap switch_gap = SwitchGap::clamp;
  MasterSurface master_surface = MasterSurface::faceted;  ///< scenes resolve it (scene/master_surface.hpp)
  std::optional<double> normal_stiffness;                 ///< ε_N; unset: 10 E ℓ (§5.1)
  std::optional<double> tangential_stiffness;             ///< ε_T; unset: 10 E ℓ
  NormalTraction normal_traction = NormalTraction::discrete_derivative;
  /// Static steps (docs/theory.md §5b.6): a Lagrange pair's slave nodes that touch the master at a step's
  /// start begin the step active, since without inertia a body held only by this contact has no other
  /// support in the first Newton pass. Set by the scene for time.scheme "static".
  bool closes_touching = false;
};

/// Why a contact pair cannot run with a time scheme: the pair's field at fault ("impact",
/// "enforcement") and the rule, in words. The one place these rules live: scene validation refuses such
/// a scene before it is queued, and the contact module refuses to build it.
struct SchemeConflict {
  std::string field;
  std::string reason;
};
/// The conflict of a pair with `enforcement` and `impact` under `scheme`, or nullopt. Rules: the velocity
/// correction (4.12) restores the identity (4.11) of the mixed energy–momentum form only; penalty contact
/// has no α-weighted (hht, generalized_alpha) form; static steps have no impacts, so a Lagrange pair closes
/// its gap there (impact exact).
std::optional<SchemeConflict> contact_scheme_conflict(Scheme scheme, Enforcement enforcement,
                                                      ImpactMode impact);

/// Time steps from t = 0 to `end` with steps of `step` (docs/scene.md, "Time"): ceil(end / step), a
/// quotient within round-off of an integer counting as that integer (a relative 1e-15 or an absolute
/// 1e-9, whichever is larger); 0 when `end` or `step` is not positive or not finite, and at most
/// max_step_count. The one count the model, the CLI and the server's early limit checks use.
long long step_count(double end, double step);
/// The largest count step_count returns (a quotient beyond it saturates here).
inline constexpr long long max_step_count = 1'000'000'000'000'000'000;

/// The most steps a run can take (the server's limits, the dry run's count): end/min_step with a
/// tolerance, else end/step; with frames at an interval plus one clipped step per frame. Arguments that
/// are not positive count as absent.
long long step_bound(double end, double step, std::optional<double> min_step, std::optional<double> interval);

struct TimeSpec {
  Scheme scheme = Scheme::energy_momentum;
  double step = 0;  ///< the fixed step, or with a tolerance the first step
  double end = 0;
  double alpha = -0.05;       ///< HHT-α only
  double rho_infinity = 0.9;  ///< generalized-α only: spectral radius at infinite frequency
  /// time.tolerance: the final largest nodal position error the step controller aims at (a length,
  /// docs/scene.md "Time"); unset: fixed steps.
  std::optional<double> tolerance;
  double min_step = 0, max_step = 0;  ///< with a tolerance: the steps the controller may choose
  bool adaptive() const { return tolerance.has_value(); }
  int steps() const;  ///< step_count(end, step); a validated scene has at most 1e9
};

/// solver.linear (docs/scene.md): auto picks direct or petsc_gamg by the element count (SolverSpec).
enum class LinearSolver { automatic, direct, iterative, petsc_gamg };
/// Every linear solver, in the order the docs list them.
inline constexpr LinearSolver all_linear_solvers[] = {LinearSolver::automatic, LinearSolver::direct,
                                                      LinearSolver::iterative, LinearSolver::petsc_gamg};
/// The scene's name of a linear solver: "auto", "direct", "iterative", "petsc_gamg".
std::string to_string(LinearSolver s);
/// The linear solver named `name`, or nullopt.
std::optional<LinearSolver> linear_solver_from_string(std::string_view name);

struct SolverSpec {
  double tolerance = 1e-10;  ///< relative residual and increment tolerance of Newton
  int max_iterations = 25;
  LinearSolver linear = LinearSolver::automatic;  ///< solver.linear
  int ranks = 1;  ///< solver.ranks: the MPI ranks the run asks for (1 when the scene does not say)
  /// auto picks petsc_gamg from this many elements on in a scene without contact: the tumbling sphere's
  /// crossover, measured on a quiet machine between 3,456 (UMFPACK 1.3× faster) and 5,880 elements (GAMG
  /// 1.3× faster) (docs/measurements.md, "Growth with size").
  static constexpr int auto_iterative_elements = 5000;
  /// The same with contact: UMFPACK was 2.2–3.1× faster than GMRES + GAMG at every size from 944 to 25,488
  /// hex8 of the refined seed example (docs/measurements.md, "Linear solvers with contact").
  static constexpr int auto_iterative_elements_with_contact = 30000;
};

struct OutputSpec {
  int every = 1;  ///< a frame every this many steps (plus the first and last)
  /// output.interval: frames at t = k·interval exactly (steps are clipped to land there) and at the end;
  /// unset: frames by `every`.
  std::optional<double> interval;
  double checkpoint_seconds = 60;  ///< a checkpoint this often (wall time) when checkpoint_every is 0
  int checkpoint_every = 0;        ///< a checkpoint every this many steps; 0: by checkpoint_seconds
  /// Whether step `step` of `steps` writes a frame: step 0, every `every`-th step and the last.
  bool frame_due(int step, int steps) const { return step % std::max(every, 1) == 0 || step == steps; }
  /// Frames a run of `steps` steps to `end` writes: frame_due counted, or with an interval
  /// step_count(end, interval) + 1 (the frames at k·interval and the end).
  long long frame_count(long long steps, double end = 0) const;
};

/// The effects a scene calls for, in a fixed vocabulary reported back to users.
namespace effect {
inline constexpr const char* inertia = "inertia";
inline constexpr const char* elasticity = "elasticity";
inline constexpr const char* gravity = "gravity";
inline constexpr const char* dirichlet = "dirichlet";
inline constexpr const char* contact_frictionless = "contact_frictionless";
inline constexpr const char* contact_frictional = "contact_frictional";
inline constexpr const char* pressure = "pressure";
inline constexpr const char* traction = "traction";
inline constexpr const char* prescribed_motion = "prescribed_motion";
inline constexpr const char* static_steps = "static";  ///< time.scheme "static", in place of inertia
}  // namespace effect

struct Model {
  std::string name;
  nlohmann::json scene;  ///< the scene as submitted, defaults filled in
  mesh::Mesh mesh;
  std::vector<BodySpec> bodies;  ///< same order as mesh.bodies
  std::vector<Boundary> boundary;
  std::vector<Load> loads;
  std::optional<Eigen::Vector3d> gravity;
  std::vector<ContactPair> contact;
  TimeSpec time;
  SolverSpec solver;
  OutputSpec output;
  std::vector<std::string> effects;  ///< resolved effect list, e.g. {"inertia","elasticity","gravity"}
  /// Contact pairs of the scene merged into one (docs/scene.md, "Pairs that share a slave"): for each
  /// merged pair of `contact`, its index there and the indices the pairs had in the scene as written.
  struct MergedPairs {
    int pair = 0;
    std::vector<int> written;
  };
  std::vector<MergedPairs> merged_contact;

  bool has_effect(const std::string& e) const;
  /// Loads or prescribed motion: work enters from outside, series/external_work (docs/theory.md §5b.5).
  bool has_external_work() const { return !loads.empty() || has_effect(effect::prescribed_motion); }
  int dof_count() const { return 3 * mesh.node_count(); }
};

/// Resolves the effect list from what the model contains (docs/scene.md); each frictional pair adds
/// "contact_frictional:<slave>,<master>" after "contact_frictional".
std::vector<std::string> resolve_effects(const Model& m);

}  // namespace stoss::model
