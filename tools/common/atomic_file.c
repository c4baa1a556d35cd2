// Atomic whole-file writes: temporary file in the target's directory, then rename(2), which
// replaces the target in one step on POSIX file systems.
#define _POSIX_C_SOURCE 200809L
#include "atomic_file.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int pool_write_file_atomic(const char *path, const char *data, size_t length, char *err,
                           size_t err_size) {
	size_t n = strlen(path);
	char *temp = malloc(n + 16);
	if (!temp) {
		snprintf(err, err_size, "%s: out of memory", path);
		return -1;
	}
	// Same directory as the target, so rename never crosses file systems.
	snprintf(temp, n + 16, "%s.tmpXXXXXX", path);
	int fd = mkstemp(temp);
	if (fd < 0) {
		snprintf(err, err_size, "%s: %s", path, strerror(errno));
		free(temp);
		return -1;
	}
	size_t done = 0;
	while (done < length) {
		ssize_t w = write(fd, data + done, length - done);
		if (w < 0) {
			if (errno == EINTR)
				continue;
			break;
		}
		done += (size_t)w;
	}
	int saved = errno;
	int ok = done == length;
	// mkstemp makes the file 0600; give it the permissions an ordinary new file would have.
	mode_t mask = umask(0);
	umask(mask);
	if (ok && fchmod(fd, 0666 & ~mask) != 0)
		saved = errno, ok = 0;
	if (close(fd) != 0 && ok)
		saved = errno, ok = 0;
	if (ok && rename(temp, path) != 0)
		saved = errno, ok = 0;
	if (!ok) {
		snprintf(err, err_size, "%s: %s", path, strerror(saved ? saved : EIO));
		unlink(temp);
	}
	free(temp);
	return ok ? 0 : -1;
}
