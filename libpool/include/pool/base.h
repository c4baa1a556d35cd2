// libpool: shared basics (vectors, results, errors, allocator).
#ifndef POOL_BASE_H
#define POOL_BASE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/// Marks the public functions: the library is built with hidden visibility, so only these are
/// exported from libpool.so and the internals stay free to change.
#if defined(__GNUC__) || defined(__clang__)
#define POOL_API __attribute__((visibility("default")))
#else
#define POOL_API
#endif

/// Library version, major * 10000 + minor * 100 + patch, of the headers compiled against.
#define POOL_VERSION 100

/// A 3D vector in the table frame (x along the length, y along the width, z up), SI units.
typedef struct pool_vec3 {
	double x; ///< m, m/s or rad/s depending on the field
	double y; ///< m, m/s or rad/s depending on the field
	double z; ///< m, m/s or rad/s depending on the field
} pool_vec3;

/// Outcome of a call: POOL_OK or a negative error code (see pool_result_str).
typedef enum pool_result {
	POOL_OK = 0,                    ///< success
	POOL_ERR_INVALID_ARGUMENT = -1, ///< a parameter is out of its valid range
	POOL_ERR_NON_FINITE = -2,       ///< a number is NaN or infinite
	POOL_ERR_OUT_OF_MEMORY = -3,    ///< the allocator failed
	POOL_ERR_OVERLAP = -4,          ///< two balls interpenetrate
	POOL_ERR_OFF_TABLE = -5,        ///< a ball is outside the playing surface
	POOL_ERR_DUPLICATE_ID = -6,     ///< two balls share an id
	POOL_ERR_UNKNOWN_BALL = -7,     ///< no ball has the given id
	POOL_ERR_BAD_STRIKE = -8,       ///< cue parameters impossible (a^2 + b^2 >= R^2, speed <= 0...)
	POOL_ERR_UNKNOWN_PRESET = -9,   ///< no table preset or model set has that name
	POOL_ERR_STATE = -10,           ///< call not allowed in the simulation's current state
	POOL_ERR_INTERNAL = -11,        ///< an invariant broke inside the library (a bug: please report)
} pool_result;

/// The version of the library linked at run time, as POOL_VERSION (major * 10000 + minor * 100 +
/// patch): a program built against one libpool and run against another can tell.
POOL_API int pool_version(void);

/// Static English description of a result code.
POOL_API const char *pool_result_str(pool_result result);

/// Detailed message of a failed call, field path first, e.g.
/// "balls[2].pos: overlaps ball 1 by 0.003 m". Optional out-parameter of validating calls.
typedef struct pool_error {
	char message[256]; ///< NUL-terminated; empty on success
} pool_error;

/// Optional allocator; zero-initialised means malloc/free. Lets tests inject failures.
typedef struct pool_allocator {
	void *(*alloc)(size_t size, void *context); ///< returns NULL on failure
	void (*free)(void *memory, void *context);  ///< releases memory from alloc (NULL is a no-op)
	void *context;                              ///< passed through unchanged
} pool_allocator;

#ifdef __cplusplus
}
#endif

#endif
