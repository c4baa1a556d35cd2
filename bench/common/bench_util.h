// What every benchmark tool needs besides the thing it measures: a clock, the median and minimum
// of its runs, and a description of the machine (docs/design.md: speed is reported as median and
// minimum of several runs plus the machine). Only libc: links into any benchmark.
#ifndef POOL_TOOLS_BENCH_UTIL_H
#define POOL_TOOLS_BENCH_UTIL_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/// Median and minimum of a set of measurements.
typedef struct pool_bench_summary {
	double median; ///< middle value; the mean of the two middle values when the count is even
	double min;    ///< smallest value
} pool_bench_summary;

/// Monotonic clock (CLOCK_MONOTONIC) in seconds, for timing runs.
double pool_bench_now_s(void);

/// Sorts values[0..count) ascending in place and returns their median and minimum; count >= 1.
pool_bench_summary pool_bench_summarise(double *values, size_t count);

/// Copies the CPU's "model name" from /proc/cpuinfo into out ("unknown" when there is none) and
/// returns out.
const char *pool_bench_cpu_model(char *out, size_t size);

/// Logical CPUs online (sysconf(_SC_NPROCESSORS_ONLN)); -1 when unknown.
long pool_bench_cpus_online(void);

#ifdef __cplusplus
}
#endif

#endif
