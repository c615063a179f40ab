/* The design search as a whole: the definition checked, a workspace per
 * thread, the scan with its edges and branches (design_scan.c), then the
 * roots (design_solve.c). */
#include "study_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Edges are bisected until their sides lie this fraction of the range
 * apart (design_scan.c). */
#define EDGE_REL_WIDTH 1e-12

/* Whether value p of the free parameter makes a valid setup. */
static int valid_at(const jc_DesignDef *def, double p, char *why, size_t why_len)
{
    jc_ParamValues v = def->fixed;
    v.given[def->free_id] = 1;
    v.value[def->free_id] = p;
    jc_Setup s = def->base;
    return jc_param_values_apply(&v, &s, NULL, why, why_len);
}

static int check(const jc_DesignDef *def, char *err, size_t err_len)
{
    const jc_ParamInfo *in = jc_param_info(def->free_id);
    if (!in) return jc_fail(err, err_len, JC_EINVAL, "design: no parameter number %d", def->free_id);
    if (in->quantity == JC_Q_NAME)
        return jc_fail(err, err_len, JC_EINVAL, "design: %s is a name, not a number (allowed: a numeric parameter)",
                       in->name);
    if (!(isfinite(def->lo) && isfinite(def->hi) && def->lo < def->hi))
        return jc_fail(err, err_len, JC_EINVAL, "design: the range %g .. %g of %s is empty (allowed: lo < hi)", def->lo,
                       def->hi, in->name);
    if (!(def->target_x_m > 0.0 && isfinite(def->target_x_m)))
        return jc_fail(err, err_len, JC_EINVAL, "design: the target %g m is not on the ramp (allowed: > 0)",
                       def->target_x_m);
    if (def->points < JC_DESIGN_POINTS_MIN || def->points > JC_DESIGN_POINTS_MAX)
        return jc_fail(err, err_len, JC_EINVAL, "design: %ld scan points (allowed: %ld to %ld)", def->points,
                       JC_DESIGN_POINTS_MIN, JC_DESIGN_POINTS_MAX);
    if (def->threads < 0) return jc_fail(err, err_len, JC_EINVAL, "design: %d threads (allowed: >= 0)", def->threads);
    const double ends[2] = {def->lo, def->hi};
    for (int k = 0; k < 2; ++k) {
        char why[256];
        if (valid_at(def, ends[k], why, sizeof why) != JC_OK)
            return jc_fail(err, err_len, JC_EINVAL, "design: %s = %g at the range's %s is not a valid setup: %s",
                           in->name, ends[k], k ? "end" : "start", why);
    }
    return JC_OK;
}

int jc_design_run(const jc_DesignDef *def, jc_DesignResult *r, char *err, size_t err_len)
{
    memset(r, 0, sizeof *r);
    const int checked = check(def, err, err_len);
    if (checked != JC_OK) return checked;
    const double t0 = jc_wall_s();
    r->threads_used = jc_thread_count(def->threads);
    r->scan_count = def->points;
    r->edge_width = (def->hi - def->lo) * EDGE_REL_WIDTH;
    r->scan = malloc((size_t)def->points * sizeof *r->scan);
    jc_Workspace **ws = calloc((size_t)r->threads_used, sizeof *ws);
    int ok = r->scan && ws;
    for (int t = 0; ok && t < r->threads_used; ++t) ok = (ws[t] = jc_workspace_new()) != NULL;
    int st = ok ? JC_OK : JC_ENOMEM;
    if (st == JC_OK) st = jc_design_scan(def, r, ws);
    if (st == JC_OK && jc_design_report(def, "roots", 0, 0)) st = JC_ESTOPPED;
    if (st == JC_OK) st = jc_design_solve(def, r, ws);
    for (int t = 0; ws && t < r->threads_used; ++t) jc_workspace_free(ws[t]);
    free(ws);
    r->seconds = jc_wall_s() - t0;
    if (st == JC_ENOMEM) return jc_fail(err, err_len, st, "design: out of memory for %ld points", def->points);
    if (st == JC_ESTOPPED) return jc_fail(err, err_len, st, "design: stopped by its caller");
    return st;
}

void jc_design_free(jc_DesignResult *r)
{
    free(r->scan);
    free(r->edges);
    free(r->branches);
    free(r->solutions);
    memset(r, 0, sizeof *r);
}
