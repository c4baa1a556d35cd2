// Live publication of a shot (see sim_publish.h).
#define _POSIX_C_SOURCE 200809L
#include "sim_publish.h"

#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lcm/lcm.h>

#include "lcm_convert.h"
#include "lcm_service.h"

struct pool_lcm_sim_publisher {
	lcm_t *lcm;
	double playback_hz;      // 0: no frames, no pacing
	int64_t shot_id;         // utime when the shot's first event was published
	int next_seq;            // seq of the next event
	long next_frame;         // index of the next playback frame (t = index / playback_hz)
	struct timespec start;   // wall clock (monotonic) of simulated t = 0
	bool started;
	bool has_def;            // the shot's setup is known (pool_lcm_sim_publisher_set_shot)
	pool_sim_def def;
	bool has_game;           // judge the shot in shot2_t
	pool_game_state game;
	char failure[256];       // first failure, reported by finish
};

static void pool_lcm_fail(pool_lcm_sim_publisher *p, const char *what)
{
	if (p->failure[0] == '\0') {
		snprintf(p->failure, sizeof p->failure, "%s", what);
	}
}

pool_lcm_sim_publisher *pool_lcm_sim_publisher_create(const char *url, double playback_hz,
                                                      char *err, size_t err_size)
{
	if (!(playback_hz >= 0.0) || !(playback_hz <= POOL_LCM_PLAYBACK_MAX_HZ)) {
		snprintf(err, err_size, "--playback: must be a rate from 0 to %g Hz",
		         POOL_LCM_PLAYBACK_MAX_HZ);
		return NULL;
	}
	pool_lcm_sim_publisher *p = calloc(1, sizeof *p);
	if (p == NULL) {
		snprintf(err, err_size, "out of memory");
		return NULL;
	}
	p->lcm = pool_lcm_open(url, err, err_size);
	if (p->lcm == NULL) {
		free(p);
		return NULL;
	}
	p->playback_hz = playback_hz;
	return p;
}

// Sleeps until simulated time t is due on the wall clock (playback only).
static void pool_lcm_wait_until(const pool_lcm_sim_publisher *p, double t)
{
	double whole = floor(t);
	struct timespec due = p->start;
	due.tv_sec += (time_t)whole;
	due.tv_nsec += (long)((t - whole) * 1e9);
	while (due.tv_nsec >= 1000000000L) {
		due.tv_nsec -= 1000000000L;
		due.tv_sec += 1;
	}
	while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &due, NULL) == EINTR) {
	}
}

// The shot starts: its id, the wall clock of t = 0, and its table on POOL_TABLE before any event.
static void pool_lcm_start(pool_lcm_sim_publisher *p)
{
	if (!p->started) {
		p->started = true;
		p->shot_id = pool_lcm_utime_now();
		clock_gettime(CLOCK_MONOTONIC, &p->start);
		if (p->has_def) {
			pool_lcm_table_t table;
			if (pool_lcm_table_fill(&p->def, p->shot_id, pool_lcm_utime_now(), &table) != 0) {
				pool_lcm_fail(p, "could not convert the table");
			} else if (pool_lcm_table_t_publish(p->lcm, POOL_LCM_CHANNEL_TABLE, &table) != 0) {
				pool_lcm_fail(p, "could not publish on " POOL_LCM_CHANNEL_TABLE);
			}
			pool_lcm_table_release(&table);
		}
	}
}

static void pool_lcm_publish_frame(pool_lcm_sim_publisher *p, const pool_sim *sim, double t)
{
	pool_lcm_wait_until(p, t);
	pool_lcm_table_state_t frame;
	if (pool_lcm_table_state_fill(sim, t, p->shot_id, pool_lcm_utime_now(), &frame) != 0) {
		pool_lcm_fail(p, "could not compute a playback frame");
		return;
	}
	if (pool_lcm_table_state_t_publish(p->lcm, POOL_LCM_CHANNEL_STATE, &frame) != 0) {
		pool_lcm_fail(p, "could not publish on " POOL_LCM_CHANNEL_STATE);
	}
	pool_lcm_table_state_release(&frame);
}

// Frames strictly before t (inclusive when `through`), each at its wall time.
static void pool_lcm_frames_until(pool_lcm_sim_publisher *p, const pool_sim *sim, double t,
                                  bool through)
{
	if (p->playback_hz <= 0.0) {
		return;
	}
	for (;;) {
		double frame_t = (double)p->next_frame / p->playback_hz;
		if (frame_t > t || (!through && frame_t == t)) {
			break;
		}
		pool_lcm_publish_frame(p, sim, frame_t);
		p->next_frame++;
	}
}

void pool_lcm_sim_publisher_event(const pool_sim *sim, const pool_event *event, void *user)
{
	pool_lcm_sim_publisher *p = user;
	pool_lcm_start(p);
	pool_lcm_frames_until(p, sim, event->time, false);
	if (p->playback_hz > 0.0) {
		pool_lcm_wait_until(p, event->time);
	}
	int count = 0;
	const pool_event *events = pool_sim_events(sim, &count);
	int seq = (int)(event - events);
	if (seq < 0 || seq >= count) {
		seq = p->next_seq; // not from the sim's array: trust the call order
	}
	// The event on POOL_EVENT, then the same with its cushion part on POOL_EVENT2.
	pool_lcm_event2_t msg;
	if (pool_lcm_event2_fill(sim, seq, p->shot_id, pool_lcm_utime_now(), &msg) != 0) {
		pool_lcm_fail(p, "could not convert an event");
	} else {
		if (pool_lcm_event_t_publish(p->lcm, POOL_LCM_CHANNEL_EVENT, &msg.event) != 0) {
			pool_lcm_fail(p, "could not publish on " POOL_LCM_CHANNEL_EVENT);
		}
		if (pool_lcm_event2_t_publish(p->lcm, POOL_LCM_CHANNEL_EVENT2, &msg) != 0) {
			pool_lcm_fail(p, "could not publish on " POOL_LCM_CHANNEL_EVENT2);
		}
	}
	pool_lcm_event2_release(&msg);
	p->next_seq = seq + 1;
}

int pool_lcm_sim_publisher_finish(pool_lcm_sim_publisher *p, const pool_sim *sim, char *err,
                                  size_t err_size)
{
	pool_lcm_start(p);
	double end = pool_sim_time(sim);
	pool_lcm_frames_until(p, sim, end, true);
	if (p->playback_hz > 0.0 && (double)(p->next_frame - 1) / p->playback_hz < end) {
		// The rest state, exactly at the end, when it does not fall on the frame grid.
		pool_lcm_publish_frame(p, sim, end);
	}
	pool_lcm_shot_t shot;
	if (pool_lcm_shot_fill(sim, p->shot_id, 0, pool_lcm_utime_now(), &shot) != 0) {
		pool_lcm_fail(p, "could not convert the shot");
	} else {
		if (pool_lcm_shot_t_publish(p->lcm, POOL_LCM_CHANNEL_SHOT, &shot) != 0) {
			pool_lcm_fail(p, "could not publish on " POOL_LCM_CHANNEL_SHOT);
		}
		pool_lcm_shot2_t shot2;
		if (pool_lcm_shot2_fill(&shot, sim, p->has_def ? &p->def : NULL, p->has_game ? &p->game : NULL,
		                        &shot2) != 0) {
			pool_lcm_fail(p, "could not convert the shot for " POOL_LCM_CHANNEL_SHOT2);
		} else {
			if (pool_lcm_shot2_t_publish(p->lcm, POOL_LCM_CHANNEL_SHOT2, &shot2) != 0) {
				pool_lcm_fail(p, "could not publish on " POOL_LCM_CHANNEL_SHOT2);
			}
			pool_lcm_shot2_release(&shot2);
		}
	}
	pool_lcm_shot_release(&shot);
	if (p->failure[0] != '\0') {
		snprintf(err, err_size, "LCM: %s", p->failure);
		return -1;
	}
	return 0;
}

void pool_lcm_sim_publisher_set_shot(pool_lcm_sim_publisher *p, const pool_sim_def *def,
                                     const pool_game_state *game)
{
	p->has_def = def != NULL;
	if (def != NULL) {
		p->def = *def;
	}
	p->has_game = def != NULL && game != NULL;
	if (p->has_game) {
		p->game = *game;
	}
}

void pool_lcm_sim_publisher_destroy(pool_lcm_sim_publisher *p)
{
	if (p != NULL) {
		lcm_destroy(p->lcm);
		free(p);
	}
}
