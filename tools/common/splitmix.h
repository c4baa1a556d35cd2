// splitmix64 (Steele, Lea & Flood 2014): the commands' own fixed random stream, the same on every
// platform and independent of pool/noise.h, so evidence campaigns and random starts do not share
// the generator of the noise they judge.
#ifndef POOL_TOOLS_SPLITMIX_H
#define POOL_TOOLS_SPLITMIX_H

#include <stdint.h>

/// A uniform deviate in the open interval (0, 1) from the stream *state (advanced by one step).
static inline double pool_splitmix_uniform(uint64_t *state) {
	uint64_t z = (*state += 0x9E3779B97F4A7C15ULL);
	z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
	z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
	z ^= z >> 31;
	return ((double)(z >> 11) + 0.5) / 9007199254740992.0;
}

#endif
