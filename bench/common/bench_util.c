// Clock, run statistics and machine description for the benchmark tools.
#define _POSIX_C_SOURCE 200809L // clock_gettime, sysconf
#include "bench_util.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

double pool_bench_now_s(void) {
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int compare_doubles(const void *a, const void *b) {
	double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

pool_bench_summary pool_bench_summarise(double *values, size_t count) {
	qsort(values, count, sizeof *values, compare_doubles);
	size_t mid = count / 2;
	pool_bench_summary s;
	s.median = count % 2 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
	s.min = values[0];
	return s;
}

const char *pool_bench_cpu_model(char *out, size_t size) {
	snprintf(out, size, "unknown");
	FILE *f = fopen("/proc/cpuinfo", "r");
	if (!f)
		return out;
	char line[512];
	while (fgets(line, sizeof line, f)) {
		if (strncmp(line, "model name", 10) == 0) {
			char *colon = strchr(line, ':');
			if (colon) {
				const char *value = colon + 1;
				while (*value == ' ' || *value == '\t')
					++value;
				snprintf(out, size, "%s", value);
				out[strcspn(out, "\n")] = '\0';
			}
			break;
		}
	}
	fclose(f);
	return out;
}

long pool_bench_cpus_online(void) {
	return sysconf(_SC_NPROCESSORS_ONLN);
}
