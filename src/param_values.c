/* Several parameter values set together over a base setup, in the table's
 * order: what a single run's options, a batch case and a design value all
 * are (<jumpcyl/study.h>). */
#include "internal.h"
#include "jumpcyl/study.h"

#include <string.h>

/* One value over the setup (jc_param_set). The parts of a body given part
 * by part keep their radii when the radius moves: only the rim moves. */
static int set_one(const jc_ParamValues *v, int id, int radius_id, jc_Setup *s, char *err, size_t err_len)
{
    const int keep_parts = v->parts_given && id == radius_id;
    jc_Part parts[JC_MAX_PARTS];
    if (keep_parts) memcpy(parts, s->body.parts, sizeof parts);
    const int st = jc_param_set(s, id, v->value[id], err, err_len);
    if (st == JC_OK && keep_parts) memcpy(s->body.parts, parts, sizeof parts);
    return st;
}

int jc_param_values_apply(const jc_ParamValues *v, jc_Setup *s, int *failed_id, char *err, size_t err_len)
{
    const int n = jc_param_count(), radius_id = jc_param_find("radius");
    int body_changed = v->parts_given;
    if (failed_id) *failed_id = -1;
    /* The body first: a disc+rod body's parameters act on the rim given with them. */
    for (int pass = 0; pass < 2; ++pass) {
        for (int id = 0; id < n; ++id) {
            const int body = (jc_param_info(id)->flags & JC_PARAM_BODY) != 0;
            if (!v->given[id] || body != (pass == 0)) continue;
            const int st = set_one(v, id, radius_id, s, err, err_len);
            if (st != JC_OK) {
                if (failed_id) *failed_id = id;
                return st;
            }
            body_changed |= body;
        }
        if (pass == 0 && body_changed) s->paper_cm_offset_m = 0.0; /* the printed d was for the paper's body */
    }
    return jc_setup_validate(s, err, err_len);
}
