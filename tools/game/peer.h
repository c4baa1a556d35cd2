// pool-game's other side: the strategy it asks for each shot, a command run as a coprocess (its
// standard input gets one turn per line, its standard output answers one line each), or the
// strikes read from pool-game's own standard input (no turns are sent then).
#ifndef POOL_TOOLS_GAME_PEER_H
#define POOL_TOOLS_GAME_PEER_H

#include <stdbool.h>
#include <stdio.h>
#include <sys/types.h>

/// The strategy: where turns go (NULL: nowhere) and where answers come from.
typedef struct game_peer {
	FILE *turns;   ///< the coprocess's standard input, or NULL
	FILE *answers; ///< its standard output, or pool-game's standard input
	pid_t pid;     ///< the coprocess, or 0
	char *line;    ///< the last answer (owned)
	size_t capacity;
} game_peer;

/// Starts `command` with /bin/sh -c. Returns 0, or -1 with errno set.
int game_peer_start(game_peer *peer, const char *command);

/// Answers from standard input, turns sent nowhere.
void game_peer_stdin(game_peer *peer);

/// Sends one turn (a line of JSON; the newline is added) and flushes. Returns 0, or -1 when the
/// strategy no longer reads.
int game_peer_send(game_peer *peer, const char *turn);

/// Reads the next answer, skipping blank lines; at most max_bytes long. Returns the line (owned by
/// the peer, without its newline), or NULL at the end of the answers (*too_long set when the line
/// was longer than max_bytes).
const char *game_peer_read(game_peer *peer, size_t max_bytes, bool *too_long);

/// Closes the pipes and waits for the coprocess. Returns its exit status (0 for standard input).
int game_peer_close(game_peer *peer);

#endif
