// Prints every event of the next shot on POOL_EVENT, then the shot from POOL_SHOT, and exits.
// cc event_subscriber.c -IBUILD/lcm_types/c BUILD/lcm_types/libpool_lcm_c.a -llcm
#include <stdio.h>

#include <lcm/lcm.h>

#include "pool_lcm_event_t.h"
#include "pool_lcm_shot_t.h"

static void on_event(const lcm_recv_buf_t *rbuf, const char *channel, const pool_lcm_event_t *e,
                     void *user)
{
	(void)rbuf, (void)channel, (void)user;
	printf("event seq=%d t=%.6f %s\n", e->seq, e->t, e->type);
	fflush(stdout); // each line at once, also into a pipe
}

static void on_shot(const lcm_recv_buf_t *rbuf, const char *channel, const pool_lcm_shot_t *s,
                    void *user)
{
	(void)rbuf, (void)channel;
	printf("shot %lld: %d events\n", (long long)s->shot_id, s->num_events);
	*(int *)user = 1;
}

int main(void)
{
	lcm_t *lcm = lcm_create("udpm://239.255.76.67:7667?ttl=0&recv_buf_size=8388608");
	if (lcm == NULL) {
		return 1;
	}
	int done = 0;
	pool_lcm_event_t_subscription_t *se =
		pool_lcm_event_t_subscribe(lcm, "POOL_EVENT", on_event, NULL);
	pool_lcm_shot_t_subscription_t *ss = pool_lcm_shot_t_subscribe(lcm, "POOL_SHOT", on_shot, &done);
	// liblcm keeps at most 30 received messages per subscription until lcm_handle takes them, and
	// drops the rest without a word; pool-sim publishes a shot's events in one burst: raise it.
	pool_lcm_event_t_subscription_set_queue_capacity(se, 10000);
	pool_lcm_shot_t_subscription_set_queue_capacity(ss, 100);
	while (!done && lcm_handle(lcm) == 0) {
	}
	pool_lcm_event_t_unsubscribe(lcm, se);
	pool_lcm_shot_t_unsubscribe(lcm, ss);
	lcm_destroy(lcm);
	return 0;
}
