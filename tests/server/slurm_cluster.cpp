#include "tests/server/slurm_cluster.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include "tests/server/live_server.hpp"

namespace stoss::test {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

/// The host's name up to its first dot: what slurmd and slurmctld call this machine.
std::string host_name() {
  std::array<char, 256> name{};
  gethostname(name.data(), name.size() - 1);
  const std::string full = name.data();
  return full.substr(0, full.find('.'));
}

/// A configuration of one node, this machine's CPUs shared by steps, no accounting, no munge.
void write_configuration(const fs::path& dir) {
  const std::string host = host_name(), d = dir.string();
  std::ofstream conf(dir / "slurm.conf");
  conf << "ClusterName=stosstest\nSlurmctldHost=" << host << "(127.0.0.1)\n"
       << "AuthType=auth/none\nCredType=cred/none\nSlurmUser=root\nSlurmdUser=root\n"
       << "SlurmctldPort=" << free_port() << "\nSlurmdPort=" << free_port() << "\n"
       << "StateSaveLocation=" << d << "/state\nSlurmdSpoolDir=" << d << "/spool\n"
       << "SlurmctldPidFile=" << d << "/slurmctld.pid\nSlurmdPidFile=" << d << "/slurmd.pid\n"
       << "SlurmctldLogFile=" << d << "/slurmctld.log\nSlurmdLogFile=" << d << "/slurmd.log\n"
       << "ProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\nMpiDefault=none\n"
       << "SchedulerType=sched/builtin\nSelectType=select/cons_tres\nSelectTypeParameters=CR_CPU\n"
       << "ReturnToService=2\nJobAcctGatherType=jobacct_gather/none\n"
       // Job ids of this cluster's own: Open MPI names a launch's shared memory after PMIx's namespace,
       // "slurm.pmix.JOB.STEP", and two clusters at once both counting from 1 crossed each other's messages.
       << "FirstJobId=" << 1000 + getpid() % 600000 * 100 << "\n"  // below MaxJobId, 67,043,328
       << "AccountingStorageType=accounting_storage/none\nKillWait=2\n"
       << "NodeName=" << host
       << " NodeAddr=127.0.0.1 CPUs=" << std::max(2u, std::thread::hardware_concurrency())
       << " State=UNKNOWN\n"
       << "PartitionName=test Nodes=" << host << " Default=YES MaxTime=INFINITE State=UP OverSubscribe=YES\n";
  // PMIx's folders per step in this cluster's directory: in /tmp they are named by job and step id alone,
  // so a cluster started at the same time, or a killed step's leftovers, would collide.
  fs::create_directories(dir / "pmix");
  std::ofstream(dir / "mpi.conf") << "PMIxCliTmpDirBase=" << d << "/pmix\n";
}

/// `program -D -f conf` in a process group of its own, its output beside its log; its pid.
pid_t start_daemon(const std::string& program, const fs::path& conf) {
  return spawn_program({program, "-D", "-f", conf.string()}, conf.parent_path() / (program + ".out"), true);
}

/// SIGTERM to the daemon's process group, SIGKILL if it is still there after 5 s; reaped.
void stop_daemon(pid_t pid) {
  if (pid <= 0) return;
  kill(-pid, SIGTERM);
  int status = 0;
  if (!eventually([&] { return waitpid(pid, &status, WNOHANG) == pid; }, 5s)) {
    kill(-pid, SIGKILL);
    waitpid(pid, &status, 0);
  }
}

}  // namespace

std::string SlurmCluster::unavailable() {
  if (geteuid() != 0) return "not root: slurmd runs steps as root here";
  for (const char* program : {"slurmctld", "slurmd", "srun"})
    if (shell_output(std::string("command -v ") + program).empty())
      return std::string(program) + " is not installed (deploy/packages.txt)";
  return {};
}

SlurmCluster::SlurmCluster() {
  std::string pattern = "/tmp/stoss-slurm-XXXXXX";
  if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot make a directory for Slurm");
  dir_ = pattern;
  fs::create_directories(dir_ / "state");
  fs::create_directories(dir_ / "spool");
  write_configuration(dir_);
  setenv("SLURM_CONF", (dir_ / "slurm.conf").c_str(), 1);
  controller_ = start_daemon("slurmctld", dir_ / "slurm.conf");
  node_daemon_ = start_daemon("slurmd", dir_ / "slurm.conf");
  if (!eventually([] { return shell_output("sinfo -h -o %T 2>/dev/null").find("idle") == 0; }, 30s)) {
    const std::string text = logs();
    stop();
    throw std::runtime_error("the Slurm cluster did not come up: " + text);
  }
}

SlurmCluster::~SlurmCluster() {
  stop();
}

void SlurmCluster::stop() {
  if (controller_ > 0) {  // the steps first, which slurmd does not end when it stops
    shell_output("scancel --full --user=root 2>/dev/null");
    eventually([] { return shell_output("squeue -h 2>/dev/null").empty(); }, 15s);
  }
  stop_daemon(node_daemon_);
  stop_daemon(controller_);
  controller_ = node_daemon_ = -1;
  unsetenv("SLURM_CONF");
  std::error_code error;
  if (!dir_.empty()) fs::remove_all(dir_, error);
  dir_.clear();
}

std::string SlurmCluster::logs() const {
  std::string text;
  for (const char* name : {"slurmctld.log", "slurmd.log"})
    text += std::string(name) + ":\n" + read_text(dir_ / name);
  return text;
}

}  // namespace stoss::test
