#include "tests/server/slurm_cluster.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include "tests/server/live_server.hpp"

extern char** environ;

namespace stoss::test {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

/// stdout of `command` through the shell (empty when it cannot run).
std::string output_of(const std::string& command) {
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return {};
  std::string out;
  std::array<char, 256> buffer{};
  while (fgets(buffer.data(), buffer.size(), pipe)) out += buffer.data();
  pclose(pipe);
  return out;
}

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
  std::vector<std::string> args{program, "-D", "-f", conf.string()};
  const fs::path out = conf.parent_path() / (program + ".out");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attributes, 0);
  pid_t pid = -1;
  const int error = posix_spawnp(&pid, program.c_str(), &actions, &attributes, argv.data(), environ);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0) throw std::runtime_error("cannot start " + program);
  return pid;
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
    if (output_of(std::string("command -v ") + program).empty())
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
  if (!eventually([] { return output_of("sinfo -h -o %T 2>/dev/null").find("idle") == 0; }, 30s)) {
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
    output_of("scancel --full --user=root 2>/dev/null");
    eventually([] { return output_of("squeue -h 2>/dev/null").empty(); }, 15s);
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
  for (const char* name : {"slurmctld.log", "slurmd.log"}) {
    std::ifstream in(dir_ / name);
    text += std::string(name) + ":\n" + std::string(std::istreambuf_iterator<char>(in), {});
  }
  return text;
}

}  // namespace stoss::test
