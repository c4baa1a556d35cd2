// Atomic whole-file writes: temporary file in the target's directory, then rename(2), which
// replaces the target in one step on POSIX file systems.
#define _XOPEN_SOURCE 700 // realpath, fchmod, mkstemp
#include "atomic_file.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "text_escape.h"

// "PATH: why", with the path escaped (it comes from the command line).
static void path_error(char *err, size_t err_size, const char *path, const char *why) {
	char shown[POOL_ESCAPE_LONG];
	snprintf(err, err_size, "%s: %s", pool_escape_str(shown, sizeof shown, path), why);
}

// Devices and pipes (/dev/null, /dev/stdout, a FIFO) are written in place: renaming a temporary
// file over them would replace the device node itself.
static int write_in_place(const char *path, const char *data, size_t length, char *err,
                          size_t err_size) {
	FILE *f = fopen(path, "wb");
	if (!f) {
		path_error(err, err_size, path, strerror(errno));
		return -1;
	}
	size_t done = fwrite(data, 1, length, f);
	int saved = errno;
	if (fclose(f) != 0 && done == length)
		saved = errno, done = 0;
	if (done != length) {
		path_error(err, err_size, path, strerror(saved ? saved : EIO));
		return -1;
	}
	return 0;
}

// Creates the directories leading to path that do not exist yet (mkdir -p of its dirname), so a
// command writes out/break.json on a fresh clone. Returns 0, or -1 with errno set.
static int make_parents(const char *path) {
	char *dir = strdup(path);
	if (!dir)
		return -1;
	char *slash = strrchr(dir, '/');
	int status = 0;
	if (slash && slash != dir) {
		*slash = '\0';
		for (char *p = dir + 1; status == 0; ++p) {
			if (*p != '/' && *p != '\0')
				continue;
			const char saved = *p;
			*p = '\0';
			struct stat st;
			if (stat(dir, &st) != 0 && (errno != ENOENT || mkdir(dir, 0777) != 0) && errno != EEXIST)
				status = -1;
			*p = saved;
			if (saved == '\0')
				break;
		}
	}
	const int saved_errno = errno;
	free(dir);
	errno = saved_errno;
	return status;
}

int pool_write_file_atomic(const char *path, const char *data, size_t length, char *err,
                           size_t err_size) {
	struct stat st;
	if (make_parents(path) != 0) {
		path_error(err, err_size, path, strerror(errno));
		return -1;
	}
	if (stat(path, &st) == 0 && !S_ISREG(st.st_mode))
		return write_in_place(path, data, length, err, err_size);
	// Through a symbolic link, replace the file it points to, not the link.
	char *real = NULL;
	if (lstat(path, &st) == 0 && S_ISLNK(st.st_mode)) {
		real = realpath(path, NULL);
		if (!real) // dangling link: let open(2) create its target
			return write_in_place(path, data, length, err, err_size);
		path = real;
	}
	size_t n = strlen(path);
	char *temp = malloc(n + 16);
	if (!temp) {
		path_error(err, err_size, path, "out of memory");
		free(real);
		return -1;
	}
	// Same directory as the target, so rename never crosses file systems.
	snprintf(temp, n + 16, "%s.tmpXXXXXX", path);
	int fd = mkstemp(temp);
	if (fd < 0) {
		path_error(err, err_size, path, strerror(errno));
		free(temp);
		free(real);
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
		path_error(err, err_size, path, strerror(saved ? saved : EIO));
		unlink(temp);
	}
	free(temp);
	free(real);
	return ok ? 0 : -1;
}
