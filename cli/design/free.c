/* design: the parameter --free NAME chooses. Which rows of the library's
 * parameter table (jumpcyl params) design can free, and each one's default
 * range, are the library's (jc_design_free_check, jc_design_default_range);
 * here they meet the command line's options and messages. */
#include "design.h"

#include <string.h>

/* The library's "NAME: why" without the name. */
static const char *reason_of(const char *msg, const char *name)
{
    const size_t n = strlen(name);
    return strncmp(msg, name, n) == 0 && strncmp(msg + n, ": ", 2) == 0 ? msg + n + 2 : msg;
}

void cli_design_free_names(int refused, char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int id = 0; id < jc_param_count() && used < len; ++id) {
        if ((jc_design_free_check(id, NULL, NULL, NULL, 0) != JC_OK) != (refused != 0)) continue;
        const int w = snprintf(buf + used, len - used, "%s%s", used ? ", " : "", jc_param_info(id)->name);
        if (w < 0) break;
        used += (size_t)w;
    }
}

/* A setup option given that sets what the free one sets (mu and mu-s). */
static int clashing_option(int free_id, const cli_SetupArgs *sa)
{
    for (int id = 0; id < jc_param_count(); ++id)
        if (sa->value[id] && (jc_param_sets(free_id, id) || jc_param_sets(id, free_id))) return id;
    return -1;
}

int cli_design_free_param(const char *name, const cli_SetupArgs *sa, cli_Param *p)
{
    const int id = jc_param_find(name);
    char allowed[512];
    cli_design_free_names(0, allowed, sizeof allowed);
    if (id < 0) {
        cli_error("design: --free '%s' is not a parameter design can choose (allowed: %s)", name, allowed);
        return EXIT_USAGE;
    }
    char why[256];
    if (jc_design_free_check(id, NULL, NULL, why, sizeof why) != JC_OK) {
        cli_error("design: --free %s: %s (allowed: %s)", name, reason_of(why, jc_param_info(id)->name), allowed);
        return EXIT_USAGE;
    }
    memset(p, 0, sizeof *p);
    cli_param_describe(id, p); /* column and unit: SI, angles in degrees */
    name = jc_param_info(id)->name;
    if (sa->value[id]) {
        cli_error("design: --%s and --free %s both given; give one (--range LO:HI bounds the search)", name, name);
        return EXIT_USAGE;
    }
    const int clash = clashing_option(id, sa);
    if (clash >= 0) {
        const char *given = jc_param_info(clash)->name;
        const int given_sets = jc_param_sets(clash, id);
        cli_error("design: --%s and --free %s both given: %s sets %s too; give one", given, name,
                  given_sets ? given : name, given_sets ? name : given);
        return EXIT_USAGE;
    }
    jc_ParamValues parts; /* the library refuses radius over a body given part by part */
    memset(&parts, 0, sizeof parts);
    parts.parts_given = sa->part_count > 0;
    if (jc_design_free_check(id, NULL, &parts, NULL, 0) != JC_OK) {
        cli_error("design: --free radius with --part bodies: choose the radius of a preset body (paper, disc, hoop)");
        return EXIT_USAGE;
    }
    return EXIT_OK;
}

/* ---- the default range ---- */

int cli_design_default_range(cli_DesignJob *job, char *note, size_t note_len)
{
    const char *name = jc_param_info(job->param.id)->name;
    char err[256];
    if (jc_design_free_check(job->param.id, &job->base, &job->values, err, sizeof err) != JC_OK) {
        cli_error("design: --free %s: %s", name, err); /* a body without the part it sets */
        return EXIT_USAGE;
    }
    jc_DesignDef def;
    memset(&def, 0, sizeof def);
    def.base = job->base;
    def.fixed = job->values;
    def.free_id = job->param.id;
    const char *rule = "";
    if (jc_design_default_range(&def, &rule, err, sizeof err) != JC_OK) {
        cli_error("design: --free %s: %s (give --range LO:HI)", name, reason_of(err, name));
        return EXIT_USAGE;
    }
    job->lo = def.lo;
    job->hi = def.hi;
    const size_t typical = strlen(JC_DESIGN_RANGE_TYPICAL);
    if (strncmp(rule, JC_DESIGN_RANGE_TYPICAL, typical) == 0) /* where the typical spans are listed */
        snprintf(note, note_len, "the default: %s ('jumpcyl params')%s", JC_DESIGN_RANGE_TYPICAL, rule + typical);
    else
        snprintf(note, note_len, "the default: %s", rule);
    return EXIT_OK;
}
