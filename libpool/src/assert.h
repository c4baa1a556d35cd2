// POOL_ASSERT: an invariant the code relies on (after SQLite's and Box2D's discipline). Errors a
// caller can cause return a pool_result; these are conditions no input can break, so a broken
// one is a bug. Checked where POOL_ASSERTS is defined (the sanitizer build, -DPOOL_SANITIZE=ON,
// or -DPOOL_ASSERTS=ON): a broken invariant prints its file, line and expression and aborts.
// Compiled out otherwise (Release): the condition is not evaluated.
#ifndef POOL_ASSERT_H
#define POOL_ASSERT_H

#ifdef POOL_ASSERTS
/// Reports a broken invariant and aborts (assert.c).
void pool_assert_failed(const char *expression, const char *detail, const char *file, int line);
#define POOL_ASSERT(condition) ((condition) ? (void)0 : pool_assert_failed(#condition, "", __FILE__, __LINE__))
/// POOL_ASSERT with a description of what broke (a string, evaluated only when it did).
#define POOL_ASSERT_MSG(condition, detail)                                                                          \
	((condition) ? (void)0 : pool_assert_failed(#condition, (detail), __FILE__, __LINE__))
#define POOL_ASSERTS_ON 1
#else
#define POOL_ASSERT(condition) ((void)sizeof(!(condition)))
#define POOL_ASSERT_MSG(condition, detail) ((void)sizeof(!(condition)), (void)sizeof(detail))
#define POOL_ASSERTS_ON 0
#endif

#endif
