// Publishing results as pool_lcm::bench_result_t on POOL_BENCH (when built with LCM).
#ifndef POOL_COMPARE_LCM_PUBLISH_H
#define POOL_COMPARE_LCM_PUBLISH_H

#include <memory>
#include <string>

#include "metrics.h"

namespace pool_compare {

/// Whether this build can publish (lcm_types generated and liblcm linked).
bool lcm_available();

/// An LCM connection publishing bench results.
class BenchPublisher {
public:
	/// Connects to url; nullptr with *error when LCM is missing or the URL is refused.
	static std::unique_ptr<BenchPublisher> open(const std::string &url, std::string *error);
	~BenchPublisher();
	/// Publishes one record on POOL_BENCH; false with *error on failure.
	bool publish(const Record &record, std::string *error);

private:
	BenchPublisher() = default;
	void *lcm_ = nullptr;
};

} // namespace pool_compare

#endif
