// Which pairs of objects touch, so that a time-stepped engine reports a collision only when a
// contact begins (docs/engines.md): a pair found touching in a step's contact pass that was not
// touching before is a new contact; a pair stops touching only once it is not found and the
// engine's own separation test says it is apart (a resting contact that flickers is one
// contact). Memory is O(contacts), not O(pairs).
#ifndef POOL_PLUGIN_CONTACT_TRACKER_H
#define POOL_PLUGIN_CONTACT_TRACKER_H

#include <algorithm>
#include <cstddef>
#include <set>
#include <utility>
#include <vector>

namespace pool_plugin {

/// Touching pairs (a, b) of object indices; what a and b index is the engine's business.
class ContactTracker {
public:
	using Pair = std::pair<size_t, size_t>;

	/// Marks a pair as touching without a new contact (contacts that exist at t = 0).
	void set_touching(size_t a, size_t b) { touching_.insert({a, b}); }
	/// Starts a step's contact pass.
	void start_pass() { seen_.clear(); }
	/// The pair touches in this pass; true when that begins a new contact.
	bool see(size_t a, size_t b) {
		seen_.push_back({a, b});
		return touching_.insert({a, b}).second;
	}
	/// Ends the pass: every touching pair not seen in it for which apart(a, b) holds is released.
	template <class Apart> void release(Apart apart) {
		std::sort(seen_.begin(), seen_.end());
		seen_.erase(std::unique(seen_.begin(), seen_.end()), seen_.end());
		for (auto it = touching_.begin(); it != touching_.end();) {
			if (!std::binary_search(seen_.begin(), seen_.end(), *it) && apart(it->first, it->second))
				it = touching_.erase(it);
			else
				++it;
		}
	}

private:
	std::set<Pair> touching_;
	std::vector<Pair> seen_;
};

} // namespace pool_plugin

#endif
