#include "lcm_publish.h"

#include <sys/time.h>

#include "results_io.h"

#ifdef POOL_COMPARE_HAVE_LCM
#include <lcm/lcm.h>

#include "pool_lcm_bench_result_t.h"
#endif

namespace pool_compare {

bool lcm_available() {
#ifdef POOL_COMPARE_HAVE_LCM
	return true;
#else
	return false;
#endif
}

std::unique_ptr<BenchPublisher> BenchPublisher::open(const std::string &url, std::string *error) {
#ifdef POOL_COMPARE_HAVE_LCM
	lcm_t *lcm = lcm_create(url.c_str());
	if (!lcm) {
		*error = "--lcm-url: cannot open LCM at '" + url + "'";
		return nullptr;
	}
	std::unique_ptr<BenchPublisher> p(new BenchPublisher());
	p->lcm_ = lcm;
	return p;
#else
	(void)url;
	*error = "--lcm-url: pool-compare was built without LCM";
	return nullptr;
#endif
}

BenchPublisher::~BenchPublisher() {
#ifdef POOL_COMPARE_HAVE_LCM
	if (lcm_)
		lcm_destroy(static_cast<lcm_t *>(lcm_));
#endif
}

bool BenchPublisher::publish(const Record &r, std::string *error) {
#ifdef POOL_COMPARE_HAVE_LCM
	// LCM carries no null: absent values travel as NaN, dt = 0 for event-driven engines.
	auto value = [](double x) { return std::isfinite(x) ? x : std::numeric_limits<double>::quiet_NaN(); };
	std::string scenario = r.scenario, engine = r.engine, reference = r.reference, json = record_json(r);
	timeval now;
	gettimeofday(&now, nullptr);
	pool_lcm_bench_result_t msg;
	msg.utime = static_cast<int64_t>(now.tv_sec) * 1000000 + now.tv_usec;
	msg.scenario = &scenario[0];
	msg.engine = &engine[0];
	msg.dt = r.event_driven ? 0.0 : value(r.dt);
	msg.cpu_seconds = value(r.cpu_seconds);
	msg.sim_seconds = value(r.sim_seconds);
	msg.final_position_error = value(r.final_position_error);
	msg.event_time_error = value(r.event_time_error);
	msg.energy_error = value(r.energy_error);
	msg.missed_collisions = r.missed_collisions;
	msg.phantom_collisions = r.phantom_collisions;
	msg.max_penetration = value(r.max_penetration);
	msg.reference = &reference[0];
	msg.json = &json[0];
	if (pool_lcm_bench_result_t_publish(static_cast<lcm_t *>(lcm_), "POOL_BENCH", &msg) != 0) {
		*error = "LCM publish on POOL_BENCH failed";
		return false;
	}
	return true;
#else
	(void)r;
	*error = "built without LCM";
	return false;
#endif
}

} // namespace pool_compare
