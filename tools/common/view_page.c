// The pool-view page of a result (view_page.h).
#include "view_page.h"

#include <stdlib.h>
#include <string.h>

// Built from tools/view/pool_view.html (tools/view/embed.cmake).
extern const char pool_view_template[];
extern const size_t pool_view_template_size;

// The data slot; the page parses what replaces its null as JSON (tools/pool-view: SLOT).
static const char slot_open[] = "<script id=\"pool-data\" type=\"application/json\">";
static const char slot_rest[] = "null</script>";
static const char lt_escaped[] = "\\u003c";

char *pool_view_page(const char *result_json) {
	const char *slot = strstr(pool_view_template, slot_open);
	if (!slot || strncmp(slot + sizeof slot_open - 1, slot_rest, sizeof slot_rest - 1) != 0)
		return NULL;
	const size_t head = (size_t)(slot - pool_view_template) + sizeof slot_open - 1;
	const char *tail = slot + sizeof slot_open - 1 + 4; // after "null"
	const size_t tail_len = pool_view_template_size - (size_t)(tail - pool_view_template);
	size_t data_len = 0;
	for (const char *c = result_json; *c; ++c)
		data_len += *c == '<' ? sizeof lt_escaped - 1 : 1;
	char *page = malloc(head + data_len + tail_len + 1);
	if (!page)
		return NULL;
	memcpy(page, pool_view_template, head);
	char *out = page + head;
	for (const char *c = result_json; *c; ++c) {
		if (*c == '<') {
			memcpy(out, lt_escaped, sizeof lt_escaped - 1);
			out += sizeof lt_escaped - 1;
		} else {
			*out++ = *c;
		}
	}
	memcpy(out, tail, tail_len);
	out[tail_len] = '\0';
	return page;
}
