#pragma once
/// @file Test support: a Slurm cluster of this one machine (Debian's slurmctld and slurmd, as root, on free
/// loopback ports, with a configuration of its own in a temporary directory, no authentication daemon),
/// started by the constructor and stopped with its steps by the destructor. SLURM_CONF names it meanwhile,
/// so srun, sinfo and the servers a test starts find it.

#include <sys/types.h>

#include <filesystem>
#include <string>

namespace stoss::test {

class SlurmCluster {
 public:
  /// Why a cluster cannot run here (Slurm not installed, not root), or empty.
  static std::string unavailable();

  SlurmCluster();
  ~SlurmCluster();
  SlurmCluster(const SlurmCluster&) = delete;
  SlurmCluster& operator=(const SlurmCluster&) = delete;

  /// The daemons' logs, for a failure's message.
  std::string logs() const;

 private:
  /// Ends the steps, stops the daemons and removes the directory; once.
  void stop();

  std::filesystem::path dir_;
  pid_t controller_ = -1, node_daemon_ = -1;
};

}  // namespace stoss::test
