#include "isolation.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#ifdef __linux__
#include <sys/prctl.h>
#endif

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

#include "results_io.h"

namespace pool_compare {

namespace {

bool write_all(int fd, const char *data, size_t size) {
	while (size > 0) {
		const ssize_t n = write(fd, data, size);
		if (n < 0 && errno == EINTR)
			continue;
		if (n <= 0)
			return false;
		data += n;
		size -= static_cast<size_t>(n);
	}
	return true;
}

// The child: runs, sends "<16 hex digits: length><record_wire>", and leaves without running the
// harness's exit handlers or flushing its buffers twice.
[[noreturn]] void child(const std::function<Record()> &run, const Record &blank, int fd, pid_t parent) {
#ifdef __linux__
	prctl(PR_SET_PDEATHSIG, SIGKILL); // a harness that dies takes its runs along
	if (getppid() != parent)
		_exit(127);
#else
	(void)parent;
#endif
	const struct rlimit no_core = {0, 0};
	setrlimit(RLIMIT_CORE, &no_core); // a crashing plugin is a result here, not a core file
	dup2(2, 1);                       // what the engine prints goes to the engine log
	signal(SIGPIPE, SIG_DFL);
	Record rec;
	try {
		rec = run();
	} catch (const std::exception &e) {
		rec = blank;
		rec.error = std::string("exception: ") + e.what();
	} catch (...) {
		rec = blank;
		rec.error = "exception";
	}
	const std::string wire = record_wire(rec);
	char header[17];
	std::snprintf(header, sizeof header, "%016llx", static_cast<unsigned long long>(wire.size()));
	std::fflush(stdout);
	std::fflush(stderr);
	_exit(write_all(fd, header, 16) && write_all(fd, wire.data(), wire.size()) ? 0 : 125);
}

std::string seconds_text(double s) {
	char buf[32];
	std::snprintf(buf, sizeof buf, "%g", s);
	return buf;
}

} // namespace

double wall_now() {
	timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

std::string signal_name(int sig) {
	static const struct {
		int number;
		const char *name;
	} names[] = {{SIGSEGV, "SIGSEGV"}, {SIGABRT, "SIGABRT"}, {SIGBUS, "SIGBUS"},   {SIGFPE, "SIGFPE"},
	             {SIGILL, "SIGILL"},   {SIGKILL, "SIGKILL"}, {SIGTERM, "SIGTERM"}, {SIGINT, "SIGINT"},
	             {SIGHUP, "SIGHUP"},   {SIGQUIT, "SIGQUIT"}, {SIGPIPE, "SIGPIPE"}, {SIGTRAP, "SIGTRAP"},
	             {SIGSYS, "SIGSYS"},   {SIGXCPU, "SIGXCPU"}, {SIGXFSZ, "SIGXFSZ"}, {SIGALRM, "SIGALRM"},
	             {SIGUSR1, "SIGUSR1"}, {SIGUSR2, "SIGUSR2"}};
	for (const auto &n : names)
		if (n.number == sig)
			return n.name;
	return "signal " + std::to_string(sig);
}

Record run_isolated(const std::function<Record()> &run, const Record &blank, double timeout, double *cpu_seconds) {
	auto failed = [&](const std::string &why, const std::string &outcome, double wall) {
		Record r = blank;
		r.error = why;
		r.outcome = outcome;
		r.wall_seconds = wall;
		return r;
	};
	if (cpu_seconds)
		*cpu_seconds = kNone;
	int fds[2];
	if (pipe(fds) != 0)
		return failed(std::string("cannot create a pipe: ") + std::strerror(errno), "failed", kNone);
	fcntl(fds[0], F_SETFD, FD_CLOEXEC);
	fcntl(fds[1], F_SETFD, FD_CLOEXEC);
	// Whatever the harness has buffered must not be written a second time by a child that exits.
	std::fflush(stdout);
	std::fflush(stderr);
	const pid_t parent = getpid();
	const double start = wall_now();
	const pid_t pid = fork();
	if (pid < 0) {
		const int e = errno;
		close(fds[0]);
		close(fds[1]);
		return failed(std::string("cannot fork: ") + std::strerror(e), "failed", kNone);
	}
	if (pid == 0) {
		close(fds[0]);
		child(run, blank, fds[1], parent);
	}
	close(fds[1]);

	const double deadline = timeout > 0.0 ? start + timeout : 0.0;
	auto remaining_ms = [&]() -> int {
		if (deadline <= 0.0)
			return -1;
		const double left = deadline - wall_now();
		return left <= 0.0 ? 0 : static_cast<int>(left * 1000.0) + 1;
	};
	std::string data;
	bool timed_out = false, eof = false;
	while (!eof && !timed_out) {
		pollfd p = {fds[0], POLLIN, 0};
		const int ms = remaining_ms();
		if (ms == 0) {
			timed_out = true;
			break;
		}
		const int r = poll(&p, 1, ms);
		if (r < 0 && errno == EINTR)
			continue;
		if (r < 0)
			break;
		if (r == 0)
			continue; // the next round sees the deadline
		char buf[65536];
		const ssize_t n = read(fds[0], buf, sizeof buf);
		if (n < 0 && errno == EINTR)
			continue;
		if (n <= 0)
			eof = true;
		else
			data.append(buf, static_cast<size_t>(n));
	}
	close(fds[0]);

	// The pipe closed (or the deadline came): the child should be gone or going. One that closed
	// the pipe and lingers is waited for until the deadline too.
	int status = 0;
	struct rusage usage {};
	pid_t got = 0;
	while (!timed_out) {
		got = wait4(pid, &status, WNOHANG, &usage);
		if (got == pid || (got < 0 && errno != EINTR))
			break;
		if (remaining_ms() == 0) {
			timed_out = true;
			break;
		}
		const timespec pause = {0, 1000000};
		nanosleep(&pause, nullptr);
	}
	if (timed_out) {
		kill(pid, SIGKILL);
		while ((got = wait4(pid, &status, 0, &usage)) < 0 && errno == EINTR) {
		}
	}
	const double wall = wall_now() - start;
	if (cpu_seconds && got == pid)
		*cpu_seconds = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
		               1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);

	if (timed_out)
		return failed("timed out after " + seconds_text(timeout) + " s", "timed_out", wall);
	if (got != pid)
		return failed(std::string("lost the run process: ") + std::strerror(errno), "failed", wall);
	if (WIFSIGNALED(status))
		return failed("killed by " + signal_name(WTERMSIG(status)), "crashed", wall);
	const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
	unsigned long long length = 0;
	const bool complete = data.size() >= 16 && std::sscanf(data.substr(0, 16).c_str(), "%16llx", &length) == 1 &&
	                      data.size() == 16 + length;
	if (code != 0 || !complete)
		return failed("exit(" + std::to_string(code) + ")", "exited", wall);
	Record rec;
	std::string error;
	if (!record_from_wire(data.substr(16), &rec, &error))
		return failed(error, "failed", wall);
	rec.outcome = rec.error.empty() ? "ok" : "failed";
	rec.wall_seconds = wall;
	return rec;
}

} // namespace pool_compare
