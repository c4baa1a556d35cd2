// Runs one engine run in a child process of its own, so a plugin that crashes, calls exit or
// hangs costs that run only: the harness records why and goes on with the others.
#ifndef POOL_COMPARE_ISOLATION_H
#define POOL_COMPARE_ISOLATION_H

#include <functional>

#include "metrics.h"

namespace pool_compare {

/// Wall-clock time, s (CLOCK_MONOTONIC).
double wall_now();

/// "SIGSEGV", "SIGABRT", ... ("signal N" for one without a name here).
std::string signal_name(int signal);

/// Forks; the child calls run() (which measures its own CPU time, as in process) and sends the
/// record back over a pipe. The parent waits at most timeout_seconds of wall-clock time (<= 0:
/// no limit), then kills the child (SIGKILL). A child killed by a signal, one that exits before
/// sending its record, and one killed at the limit give `blank` with error "killed by SIGSEGV",
/// "exit(3)" or "timed out after N s" and outcome "crashed", "exited" or "timed_out". The
/// child's standard output and error are the parent's standard error (the engine log). Sets
/// wall_seconds, and *cpu_seconds (when given) to the child's CPU time (user + system).
Record run_isolated(const std::function<Record()> &run, const Record &blank, double timeout_seconds,
                    double *cpu_seconds = nullptr);

} // namespace pool_compare

#endif
