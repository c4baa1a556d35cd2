// The pool-view page of a result: the page template (tools/view/pool_view.html, built into the
// program) with a libpool-result/1 document in its data slot. pool-sim --view writes it; the
// pool-view command writes the same bytes from a result file.
#ifndef POOL_TOOLS_VIEW_PAGE_H
#define POOL_TOOLS_VIEW_PAGE_H

#ifdef __cplusplus
extern "C" {
#endif

/// The page holding result_json (its text as written, every '<' as \u003c so nothing in it can
/// end the page's script element), malloc'd and NUL-terminated; NULL when out of memory or when
/// the template has no data slot.
char *pool_view_page(const char *result_json);

#ifdef __cplusplus
}
#endif

#endif
