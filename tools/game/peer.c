// pool-game's strategy process and line I/O (peer.h).
#define _POSIX_C_SOURCE 200809L
#include "peer.h"

#include <errno.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

int game_peer_start(game_peer *peer, const char *command) {
	memset(peer, 0, sizeof *peer);
	int to_child[2], from_child[2];
	if (pipe(to_child) != 0)
		return -1;
	if (pipe(from_child) != 0) {
		close(to_child[0]);
		close(to_child[1]);
		return -1;
	}
	// A strategy that exits early must not kill pool-game with SIGPIPE: writes then fail with EPIPE.
	signal(SIGPIPE, SIG_IGN);
	const pid_t pid = fork();
	if (pid < 0) {
		const int e = errno;
		close(to_child[0]), close(to_child[1]), close(from_child[0]), close(from_child[1]);
		errno = e;
		return -1;
	}
	if (pid == 0) {
		dup2(to_child[0], STDIN_FILENO);
		dup2(from_child[1], STDOUT_FILENO);
		close(to_child[0]), close(to_child[1]), close(from_child[0]), close(from_child[1]);
		execl("/bin/sh", "sh", "-c", command, (char *)NULL);
		_exit(127);
	}
	close(to_child[0]);
	close(from_child[1]);
	peer->turns = fdopen(to_child[1], "w");
	peer->answers = fdopen(from_child[0], "r");
	peer->pid = pid;
	if (!peer->turns || !peer->answers) {
		game_peer_close(peer);
		errno = ENOMEM;
		return -1;
	}
	return 0;
}

void game_peer_stdin(game_peer *peer) {
	memset(peer, 0, sizeof *peer);
	peer->answers = stdin;
}

int game_peer_send(game_peer *peer, const char *turn) {
	if (!peer->turns)
		return 0;
	if (fputs(turn, peer->turns) == EOF || fputc('\n', peer->turns) == EOF || fflush(peer->turns) != 0)
		return -1;
	return 0;
}

const char *game_peer_read(game_peer *peer, size_t max_bytes, bool *too_long) {
	*too_long = false;
	for (;;) {
		size_t n = 0;
		int c;
		while ((c = fgetc(peer->answers)) != EOF && c != '\n') {
			if (n >= max_bytes) {
				*too_long = true;
				return NULL;
			}
			if (n + 2 > peer->capacity) {
				const size_t capacity = peer->capacity ? 2 * peer->capacity : 1024;
				char *line = realloc(peer->line, capacity);
				if (!line)
					return NULL;
				peer->line = line;
				peer->capacity = capacity;
			}
			peer->line[n++] = (char)c;
		}
		if (c == EOF && n == 0)
			return NULL;
		peer->line[n] = '\0';
		if (n > 0 && peer->line[n - 1] == '\r')
			peer->line[--n] = '\0';
		size_t blank = 0;
		while (blank < n && (peer->line[blank] == ' ' || peer->line[blank] == '\t'))
			++blank;
		if (blank < n)
			return peer->line;
		if (c == EOF)
			return NULL;
	}
}

int game_peer_close(game_peer *peer) {
	int status = 0;
	if (peer->turns)
		fclose(peer->turns);
	if (peer->pid > 0) {
		if (peer->answers)
			fclose(peer->answers);
		int wstatus = 0;
		while (waitpid(peer->pid, &wstatus, 0) < 0 && errno == EINTR) {
		}
		status = WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : 128 + (WIFSIGNALED(wstatus) ? WTERMSIG(wstatus) : 0);
	}
	free(peer->line);
	memset(peer, 0, sizeof *peer);
	return status;
}
