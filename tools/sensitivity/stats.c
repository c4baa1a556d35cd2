// The statistics of a cloud of final positions and of pocketing counts.
//
// Mean and sample covariance (n - 1) are GSL's (gsl_stats_mean, gsl_stats_variance_m,
// gsl_stats_covariance_m), over the samples whose ball ended on the table, in sample order.
// The 95 % ellipse is the region of a bivariate normal with that mean and covariance holding
// 95 % of it: Mahalanobis distance^2 <= q = -2 ln(0.05) = 5.99146 (the chi-square quantile of 2
// degrees of freedom, whose CDF is 1 - exp(-q/2)). Its semi-axes are sqrt(q lambda) for the
// covariance's eigenvalues lambda = (xx + yy)/2 +- hypot((xx - yy)/2, xy), its major axis at
// 1/2 atan2(2 xy, xx - yy) from +x.
// Proportions carry Wilson's score interval (Wilson 1927): with p = k/n and z the normal
// quantile, centre (p + z^2/2n) / (1 + z^2/n), half-width z/(1 + z^2/n) sqrt(p(1-p)/n + z^2/4n^2).
// Unlike p +- z sqrt(p(1-p)/n) it stays inside [0, 1] and does not shrink to nothing at k = 0
// or k = n, which is where a pocketing probability of a good shot lives.
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "study.h"

#define SENS_RAD_TO_DEG (180.0 / 3.14159265358979323846)

double sens_chi2_2dof(void) { return -2.0 * log(1.0 - SENS_CONFIDENCE); }

double sens_z(void) { return gsl_cdf_ugaussian_Pinv(0.5 + SENS_CONFIDENCE / 2.0); }

sens_proportion sens_wilson(long count, long n) {
	sens_proportion r = {.count = count, .n = n, .p = NAN, .low = NAN, .high = NAN};
	if (n <= 0)
		return r;
	double z = sens_z(), nn = (double)n, p = (double)count / nn;
	double denominator = 1.0 + z * z / nn;
	double centre = (p + z * z / (2.0 * nn)) / denominator;
	double half = z / denominator * sqrt(p * (1.0 - p) / nn + z * z / (4.0 * nn * nn));
	r.p = p;
	r.low = fmax(0.0, centre - half);
	r.high = fmin(1.0, centre + half);
	return r;
}

int sens_cloud_compute(const sens_run *r, int k, int32_t id, sens_cloud *out) {
	memset(out, 0, sizeof *out);
	out->id = id;
	int t = r->tracked_count;
	long pocketed = 0, off_table = 0, per_pocket[SENS_POCKET_COUNT] = {0};
	double *x = malloc(((size_t)r->n + 1) * sizeof *x), *y = malloc(((size_t)r->n + 1) * sizeof *y);
	if (!x || !y) {
		free(x);
		free(y);
		return -1;
	}
	long m = 0;
	for (long i = 0; i < r->n; ++i) {
		if (r->stop[i] < 0)
			continue;
		out->samples++;
		int8_t state = r->state[i * t + k];
		if (state == POOL_MOTION_POCKETED) {
			pocketed++;
			int8_t p = r->pocket[i * t + k];
			if (p >= 0 && p < SENS_POCKET_COUNT)
				per_pocket[p]++;
		} else if (state == POOL_MOTION_OFF_TABLE) {
			off_table++;
		} else {
			x[m] = r->pos[(i * t + k) * 2];
			y[m] = r->pos[(i * t + k) * 2 + 1];
			m++;
		}
	}
	out->on_table = out->samples - pocketed - off_table;
	out->pocketed = sens_wilson(pocketed, out->samples);
	out->off_table = sens_wilson(off_table, out->samples);
	for (int p = 0; p < SENS_POCKET_COUNT; ++p)
		out->pockets[p] = sens_wilson(per_pocket[p], out->samples);
	if (m >= 1) {
		out->has_mean = true;
		out->mean[0] = gsl_stats_mean(x, 1, (size_t)m);
		out->mean[1] = gsl_stats_mean(y, 1, (size_t)m);
	}
	if (m >= 2) {
		out->has_cov = true;
		double xx = gsl_stats_variance_m(x, 1, (size_t)m, out->mean[0]);
		double yy = gsl_stats_variance_m(y, 1, (size_t)m, out->mean[1]);
		double xy = gsl_stats_covariance_m(x, 1, y, 1, (size_t)m, out->mean[0], out->mean[1]);
		out->cov[0] = xx;
		out->cov[1] = xy;
		out->cov[2] = yy;
		double centre = 0.5 * (xx + yy), radius = hypot(0.5 * (xx - yy), xy);
		double q = sens_chi2_2dof();
		out->ellipse_major = sqrt(q * (centre + radius));
		out->ellipse_minor = sqrt(q * fmax(0.0, centre - radius)); // >= 0 despite rounding
		double angle = (xy == 0.0 && xx >= yy) ? 0.0 : 0.5 * atan2(2.0 * xy, xx - yy) * SENS_RAD_TO_DEG;
		out->ellipse_angle_deg = angle <= -90.0 ? angle + 180.0 : angle;
	}
	free(x);
	free(y);
	return 0;
}

sens_game_stats sens_game_stats_compute(const sens_run *r) {
	sens_game_stats g;
	memset(&g, 0, sizeof g);
	long legal = 0, legal_pot = 0, outcomes[4] = {0, 0, 0, 0};
	for (long i = 0; r->legal && i < r->n; ++i) {
		if (r->stop[i] < 0)
			continue;
		g.samples++;
		legal += r->legal[i] == 1;
		if (r->outcome[i] >= 0 && r->outcome[i] < 4)
			outcomes[r->outcome[i]]++;
		legal_pot += r->legal[i] == 1 &&
		             (r->outcome[i] == POOL_OUTCOME_CONTINUE || r->outcome[i] == POOL_OUTCOME_WIN);
	}
	g.legal = sens_wilson(legal, g.samples);
	g.legal_pot = sens_wilson(legal_pot, g.samples);
	for (int k = 0; k < 4; ++k)
		g.outcomes[k] = sens_wilson(outcomes[k], g.samples);
	return g;
}
