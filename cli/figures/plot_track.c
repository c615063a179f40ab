/* The figure of `compare` and `fit`: a tracked experiment over the model.
 * The data go into the script as data blocks, and every word in it is the
 * tool's own: nothing from the track file (names, text) reaches gnuplot. */
#include "figures.h"

#include <errno.h>
#include <math.h>
#include <string.h>

static void put(FILE *f, double v)
{
    if (isfinite(v)) fprintf(f, " %.10g", v);
    else fputs(" NaN", f);
}

/* The frames' residuals in units of sigma (jc_track_residuals_frame, as the fit
 * has them): the centre along and across the incline and the mark across
 * its radius (a tracked centre), or the mark along and across (a centre
 * recovered from the mark); NaN where the frame has none. */
static void residuals_at(const cli_TrackFigure *f, long i, double r[3])
{
    const double s = f->sigma_m > 0 ? f->sigma_m : f->track->sigma_m;
    r[0] = r[1] = r[2] = NAN;
    jc_track_residuals_frame(f->track, f->first + i, s, f->mark_radius_m, f->sim_x[i], f->sim_y[i], f->sim_theta[i], r);
}

static void write_data(FILE *gp, const cli_TrackFigure *f)
{
    const jc_Track *t = f->track;
    fig_block_begin(gp, "frames");
    fputs("# t_s x_cm height_mm height_sigma_mm r_along r_across r_mark (residuals in sigma)\n", gp);
    for (long i = 0; i < f->count; ++i) {
        const long j = f->first + i;
        double r[3];
        residuals_at(f, i, r);
        fprintf(gp, "%.10g", t->t_s[j]);
        put(gp, t->x_m[j] * 100);
        put(gp, (t->y_m[j] - f->radius_m) * 1e3);
        /* An error bar is shown up to 5 noises: the frames where a mark alone
         * tells the centre least would else set the panel's scale. */
        put(gp, fmin(t->centre_sigma_m[j], 5.0 * t->sigma_m) * 1e3);
        put(gp, r[0]);
        put(gp, r[1]);
        put(gp, r[2]);
        fputc('\n', gp);
    }
    fig_block_end(gp);
    fig_block_begin(gp, "model");
    fputs("# t_s x_cm height_mm\n", gp);
    for (long i = 0; i < f->path_n; ++i) {
        fprintf(gp, "%.10g", f->path_t[i]);
        put(gp, f->path_x[i] * 100);
        put(gp, (f->path_y[i] - f->radius_m) * 1e3);
        fputc('\n', gp);
    }
    fig_block_end(gp);
}

static void write_panels(FILE *gp, const cli_TrackFigure *f)
{
    const int from_mark = f->track->centre_source == JC_TRACK_CENTRE_FROM_MARK;
    fputs("\nset multiplot layout 3,1 title ", gp);
    fig_quote(gp, f->title);
    fputs(" font F_TITLE\n", gp);
    fig_panel_begin(gp, "the centre along the incline");
    fputs("set title 'The centre along the incline'\nset xlabel 't (s)'\nset ylabel 'x (cm)'\n"
          "set autoscale xfix\nset offsets 0, 0, graph 0.05, graph 0.05\n"
          "plot $model u 1:2 w l lc rgb C_BLUE lw LW t 'model', \\\n"
          "     $frames u 1:2 w p pt 6 ps 0.9*PS lc rgb C_RED t 'video'\n",
          gp);
    fig_panel_begin(gp, "the centre's height above the surface");
    fprintf(gp,
            "set title 'The centre above the surface (hops show as arches)'\nset xlabel 't (s)'\n"
            "set ylabel 'height above contact (mm)'\nset autoscale xfix\nset offsets 0, 0, graph 0.05, graph 0.05\n"
            "plot $model u 1:3 w l lc rgb C_BLUE lw LW t 'model', \\\n"
            "     $frames u 1:3:4 w yerrorbars pt 6 ps 0.9*PS lc rgb C_RED t '%s', \\\n"
            "     %.10g w l dt 2 lc rgb C_GREY lw 2 t 'hop threshold'\n",
            from_mark ? "video (centre recovered from the mark)" : "video", f->hop_threshold_m * 1e3);
    fig_panel_begin(gp, "residuals in units of sigma");
    fprintf(gp, "set title 'Residuals: video minus model, in units of the noise (%.2f mm)'\nset xlabel 't (s)'\n"
                "set ylabel 'residual / sigma'\nset autoscale xfix\nset yrange [*<-4:4<*]\n"
                "plot 3 w l dt 2 lc rgb C_GREY lw 1 t '±3 sigma', -3 w l dt 2 lc rgb C_GREY lw 1 notitle, \\\n"
                "     $frames u 1:5 w p pt 7 ps 0.6*PS lc rgb C_BLUE t '%s', \\\n"
                "     $frames u 1:6 w p pt 5 ps 0.6*PS lc rgb C_ORANGE t '%s'",
            (f->sigma_m > 0 ? f->sigma_m : f->track->sigma_m) * 1e3,
            from_mark ? "mark, along the incline" : "centre, along the incline",
            from_mark ? "mark, across the incline" : "centre, across the incline");
    if (!from_mark && f->mark_radius_m > 0.0)
        fputs(", \\\n     $frames u 1:7 w p pt 9 ps 0.6*PS lc rgb C_GREEN t 'mark, across its radius'", gp);
    fputs("\nunset multiplot\n", gp);
}

static int write_script(const cli_TrackFigure *f, fig_Format format, const char *output, const char *cmdline,
                        const char *script)
{
    FILE *gp = fopen(script, "w");
    if (!gp) {
        cli_error("cannot write %s: %s", script, strerror(errno));
        return EXIT_FAIL;
    }
    const char *slash = strrchr(output, '/');
    char base[256];
    cli_safe_name(slash ? slash + 1 : output, base, sizeof base);
    fig_script_begin(gp, format, 1, 3, base, cmdline);
    fputs("\n# ---- Data ----\n", gp);
    write_data(gp, f);
    write_panels(gp, f);
    int err = fflush(gp) != 0 ? errno : 0;
    if (!err && ferror(gp)) err = EIO;
    if (fclose(gp) != 0 && !err) err = errno;
    if (err) {
        cli_error("cannot write %s: %s (writing its script %s)", output, strerror(err), script);
        return EXIT_FAIL;
    }
    return EXIT_OK;
}

static int publish(const char *output, fig_Format format, const char *figure)
{
    cli_Output fig;
    if (cli_output_begin(&fig, output, 0) != 0) return EXIT_FAIL;
    const int ok = cli_output_copy_from(&fig, figure) == 0 && cli_output_finish(&fig, fig_check(format)) == 0 &&
                   cli_output_publish(&fig) == 0;
    cli_output_abort(&fig);
    if (!ok && cli_stop_requested()) return cli_stop_status();
    return ok ? EXIT_OK : EXIT_FAIL;
}

int cli_track_figure(const char *cmd, const cli_TrackFigure *f, const char *output, const char *cmdline)
{
    fig_Format format;
    if (fig_format_from_path(output, &format) != 0) {
        cli_error("%s: --output '%s': the format follows the extension (allowed: .png, .svg, .pdf)", cmd, output);
        return EXIT_USAGE;
    }
    cli_WorkDir work;
    if (cli_workdir_make(&work, cmd) != 0) return EXIT_FAIL;
    char script[CLI_PATH_MAX], figure[CLI_PATH_MAX];
    int rc = EXIT_OK;
    if (cli_path_join(script, sizeof script, work.path, FIG_SCRIPT_NAME) != 0 ||
        cli_path_join(figure, sizeof figure, work.path, fig_scratch_name(format)) != 0) {
        cli_error("%s: scratch path too long: %s", cmd, work.path);
        rc = EXIT_FAIL;
    }
    if (rc == EXIT_OK) rc = write_script(f, format, output, cmdline, script);
    if (rc == EXIT_OK) rc = fig_render(cmd, work.path, format, output);
    if (rc == EXIT_OK) rc = publish(output, format, figure);
    cli_workdir_remove(&work);
    if (rc != EXIT_OK && cli_stop_requested()) rc = cli_stop_status();
    return rc;
}
