// The options of a search as text: the noise, the kinds, the pocket.
#include <stdio.h>
#include <string.h>

#include "aim_tool.h"
#include "text_escape.h"

int aim_parse_noise(const char *spec, pool_noise *noise, char *err, size_t err_size) {
	pool_error e;
	if (pool_noise_parse(spec, noise, &e) != POOL_OK) {
		snprintf(err, err_size, "%s", e.message);
		return -1;
	}
	return 0;
}

int aim_parse_kinds(const char *spec, unsigned *kinds, char *err, size_t err_size) {
	*kinds = 0;
	if (strcmp(spec, "all") == 0)
		return 0;
	for (const char *p = spec;;) {
		size_t n = strcspn(p, ",");
		char name[32];
		int kind = -1;
		if (n > 0 && n < sizeof name) {
			memcpy(name, p, n);
			name[n] = '\0';
			kind = pool_aim_kind_from_name(name);
		}
		if (kind < 0) {
			char shown[POOL_ESCAPE_SHORT];
			pool_escape_text(shown, sizeof shown, p, n);
			snprintf(err, err_size, "kinds: '%s' is not a kind of shot (straight, bank, kick, combination, carom, "
			         "or all)", shown);
			return -1;
		}
		*kinds |= 1u << kind;
		if (!p[n])
			return 0;
		p += n + 1;
	}
}

int aim_parse_pocket(const char *name, pool_pocket *pocket, char *err, size_t err_size) {
	for (int p = POOL_POCKET_SW; p <= POOL_POCKET_N; ++p)
		if (strcmp(name, pool_pocket_name((pool_pocket)p)) == 0) {
			*pocket = (pool_pocket)p;
			return 0;
		}
	char shown[POOL_ESCAPE_SHORT];
	pool_escape_str(shown, sizeof shown, name);
	snprintf(err, err_size, "pocket: '%s' is not a pocket (sw, se, nw, ne, s, n)", shown);
	return -1;
}
