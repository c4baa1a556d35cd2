// The deepest overlap among equal spheres, for a plugin's max_penetration statistic after every
// step. Testing every pair is quadratic: at 1,024 balls it took 35 % of a Bullet step, a cost of
// the measurement, not of the engine. Balls are binned in square cells of one diameter in the
// plane, so only balls in the same or a neighbouring cell can overlap; every such pair is tested
// with the same formula as the all-pairs loop, so the result is the same to the bit.
#ifndef POOL_PLUGIN_SPHERE_OVERLAP_H
#define POOL_PLUGIN_SPHERE_OVERLAP_H

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace pool_plugin {

/// Finds the deepest overlap 2R - |pi - pj| among spheres of radius R; reusable between steps.
class SphereOverlap {
public:
	/// Below this many spheres every pair is tested: binning costs more than it saves.
	static constexpr size_t kAllPairsUpTo = 48;

	/// The deepest overlap (m) among the centres, or 0 when none overlap.
	double deepest(const std::vector<std::array<double, 3>> &centres, double radius) {
		const size_t n = centres.size();
		const double diameter = 2.0 * radius, touch2 = 4.0 * radius * radius;
		double deepest = 0.0;
		auto test = [&](size_t i, size_t j) {
			const double dx = centres[i][0] - centres[j][0], dy = centres[i][1] - centres[j][1],
			             dz = centres[i][2] - centres[j][2];
			const double d2 = dx * dx + dy * dy + dz * dz;
			if (d2 < touch2)
				deepest = std::max(deepest, diameter - std::sqrt(d2));
		};
		if (n <= kAllPairsUpTo) {
			for (size_t i = 0; i < n; ++i)
				for (size_t j = i + 1; j < n; ++j)
					test(i, j);
			return deepest;
		}
		// Cells of one diameter: overlapping centres are less than a diameter apart in x and y,
		// so they lie in the same cell or in one of its eight neighbours.
		cells_.clear();
		for (size_t i = 0; i < n; ++i)
			cells_.push_back({cell_key(std::floor(centres[i][0] / diameter), std::floor(centres[i][1] / diameter)),
			                  static_cast<uint32_t>(i)});
		std::sort(cells_.begin(), cells_.end());
		for (size_t a = 0; a < n; ++a) {
			const uint32_t i = cells_[a].second;
			const double cx = std::floor(centres[i][0] / diameter), cy = std::floor(centres[i][1] / diameter);
			// Each unordered pair once: the neighbours at or after this cell in key order (same cell:
			// later entries only).
			for (int ox = 0; ox <= 1; ++ox)
				for (int oy = -1; oy <= 1; ++oy) {
					if (ox == 0 && oy < 0)
						continue;
					const int64_t key = cell_key(cx + ox, cy + oy);
					auto it = std::lower_bound(cells_.begin(), cells_.end(), std::make_pair(key, uint32_t(0)));
					if (ox == 0 && oy == 0)
						it = cells_.begin() + static_cast<std::ptrdiff_t>(a) + 1;
					for (; it != cells_.end() && it->first == key; ++it)
						test(i, it->second);
				}
		}
		return deepest;
	}

private:
	// Cell coordinates of any table (|x| / diameter far below 2^31) packed into one sortable key.
	static int64_t cell_key(double cx, double cy) {
		return static_cast<int64_t>(cx) * (int64_t(1) << 32) + (static_cast<int64_t>(cy) + (int64_t(1) << 31));
	}

	std::vector<std::pair<int64_t, uint32_t>> cells_;
};

} // namespace pool_plugin

#endif
