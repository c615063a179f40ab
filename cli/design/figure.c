/* design --figure: the first lift-off against the free option, one curve
 * per continuous branch (so no line is drawn across a leap), the
 * discontinuities as dotted verticals, the ranges without a lift-off
 * shaded, X as a line and the solutions marked. */
#include "design.h"
#include "figures.h"

#include <errno.h>
#include <math.h>
#include <string.h>

/* The branches' points: scan points inside, edge sides at the ends; a blank
 * line between branches breaks the curve. */
static void write_branches(FILE *gp, const jc_DesignResult *r, double per_si)
{
    fig_block_begin(gp, "branches");
    fputs("# columns: free option (display unit), first lift-off (cm); a blank line ends a branch\n", gp);
    long i = 0;
    for (int k = 0; k < r->branch_count; ++k) {
        const jc_DesignBranch *b = &r->branches[k];
        if (b->kind != JC_CASE_LIFTOFF) continue;
        const jc_DesignPoint *first = k > 0 ? &r->edges[k - 1].hi : NULL;
        const jc_DesignPoint *last = k < r->edge_count ? &r->edges[k].lo : NULL;
        if (first) fprintf(gp, "%.12g %.12g\n", first->p * per_si, first->x_m * 100);
        for (i = 0; i < r->scan_count; ++i) {
            const jc_DesignPoint *s = &r->scan[i];
            if (s->p >= b->p_lo && s->p <= b->p_hi && s->kind == JC_CASE_LIFTOFF)
                fprintf(gp, "%.12g %.12g\n", s->p * per_si, s->x_m * 100);
        }
        if (last) fprintf(gp, "%.12g %.12g\n", last->p * per_si, last->x_m * 100);
        fputs("\n", gp);
    }
    fig_block_end(gp);
}

static void write_script(FILE *gp, const cli_DesignJob *job, const jc_DesignResult *r, fig_Format f,
                         const char *base, const char *cmdline)
{
    const cli_DesignUnits u = cli_design_units(job);
    const char *name = jc_param_info(job->param.id)->name;
    fig_script_begin(gp, f, 1, 1, base, cmdline);
    fputs("\n# ---- Data ----\n", gp);
    write_branches(gp, r, u.per_si);
    fig_block_begin(gp, "solutions");
    fputs("# columns: free option (display unit), first lift-off (cm)\n", gp);
    for (int k = 0; k < r->solution_count; ++k)
        fprintf(gp, "%.12g %.12g\n", r->solutions[k].p * u.per_si, r->solutions[k].x_m * 100);
    if (r->solution_count == 0) fputs("NaN NaN\n", gp); /* an empty block would be an error to plot */
    fig_block_end(gp);
    fig_panel_begin(gp, "design");
    jc_Model m;
    char err[256], caption[256] = "", body[256] = "";
    if (jc_model_init(&m, &job->nominal, err, sizeof err) == JC_OK) {
        fig_caption(&m, caption, sizeof caption);
        fig_body_caption(&m, body, sizeof body);
    }
    fprintf(gp, "set title sprintf(\"First lift-off against %s: X = %.4g cm, %d solution%s\\n{/*0.8 %%s; %%s}\", ",
            name, job->target_m * 100, r->solution_count, r->solution_count == 1 ? "" : "s");
    fig_quote(gp, caption);
    fputs(", ", gp);
    fig_quote(gp, body);
    fputs(")\n", gp);
    fprintf(gp, "set xlabel '%s%s'\nset ylabel 'first lift-off down the ramp (cm)'\n", name, u.paren);
    fprintf(gp, "set xrange [%.12g:%.12g]\n", job->lo * u.per_si, job->hi * u.per_si);
    /* The lift-offs and X decide the vertical range: a narrow --range would
     * flatten its curve against the whole ramp's. */
    fputs("set autoscale y\nset offsets 0, 0, graph 0.08, graph 0.08\n", gp);
    int obj = 1;
    for (int k = 0; k < r->branch_count; ++k) {
        const jc_DesignBranch *b = &r->branches[k];
        if (b->kind == JC_CASE_LIFTOFF) continue;
        fprintf(gp, "set object %d rect from %.12g, graph 0 to %.12g, graph 1 behind fc rgb C_GREY fs transparent "
                    "solid 0.15 noborder\n",
                obj++, b->p_lo * u.per_si, b->p_hi * u.per_si);
    }
    for (int k = 0; k < r->edge_count; ++k) {
        const double p = 0.5 * (r->edges[k].lo.p + r->edges[k].hi.p) * u.per_si;
        fprintf(gp, "set arrow from %.12g, graph 0 to %.12g, graph 1 nohead dt 3 lw 1.2 lc rgb C_GREY\n", p, p);
    }
    fprintf(gp,
            "set key below center horizontal maxcols 3 maxrows 2\n"
            "plot $branches using 1:2 with lines lw LW lc rgb C_BLUE title 'first lift-off', \\\n"
            "     %.12g with lines lw 2 dt 2 lc rgb C_RED title 'X', \\\n"
            "     NaN with lines dt 3 lw 1.2 lc rgb C_GREY title 'discontinuity', \\\n"
            "     NaN with boxes fs transparent solid 0.15 noborder fc rgb C_GREY title 'no lift-off', \\\n"
            "     $solutions using 1:2 with points pt 7 ps 2.2*PS lc rgb C_INK title 'solutions'\n",
            job->target_m * 100);
}

int cli_design_figure(const cli_DesignJob *job, const jc_DesignResult *r, const char *path, const char *cmdline)
{
    fig_Format f;
    if (fig_format_from_path(path, &f) != 0) return EXIT_USAGE; /* checked before the search */
    cli_WorkDir work;
    if (cli_workdir_make(&work, "design") != 0) return EXIT_FAIL;
    char script[CLI_PATH_MAX], figure[CLI_PATH_MAX], base[256];
    int rc = EXIT_OK;
    if (cli_path_join(script, sizeof script, work.path, FIG_SCRIPT_NAME) != 0 ||
        cli_path_join(figure, sizeof figure, work.path, fig_scratch_name(f)) != 0) {
        cli_error("design: scratch path too long: %s", work.path);
        rc = EXIT_FAIL;
    }
    const char *slash = strrchr(path, '/');
    cli_safe_name(slash ? slash + 1 : path, base, sizeof base);
    FILE *gp = rc == EXIT_OK ? fopen(script, "w") : NULL;
    if (rc == EXIT_OK && !gp) {
        cli_error("cannot write %s: %s (its script)", path, strerror(errno));
        rc = EXIT_FAIL;
    }
    if (gp) {
        write_script(gp, job, r, f, base, cmdline);
        if (fclose(gp) != 0) {
            cli_error("cannot write %s: %s (its script)", path, strerror(errno));
            rc = EXIT_FAIL;
        }
    }
    if (rc == EXIT_OK) rc = fig_render("design", work.path, f, path);
    if (rc == EXIT_OK) {
        cli_Output out;
        memset(&out, 0, sizeof out);
        if (cli_output_begin(&out, path, 0) != 0 || cli_output_copy_from(&out, figure) != 0 ||
            cli_output_commit(&out, fig_check(f)) != 0) {
            cli_output_abort(&out);
            rc = EXIT_FAIL;
        }
    }
    cli_workdir_remove(&work);
    if (rc != EXIT_OK && cli_stop_requested()) rc = cli_stop_status();
    return rc;
}
