/* The figure of `compare` and `fit`: a tracked experiment over the model.
 * The data go into the script as data blocks, and every word in it is the
 * tool's own: nothing from the track file (names, text) reaches gnuplot. */
#include "plot.h"
#include "track_fit.h"

#include <errno.h>
#include <math.h>
#include <string.h>

static void put(FILE *f, double v)
{
    if (isfinite(v)) fprintf(f, " %.10g", v);
    else fputs(" NaN", f);
}

/* Incline frame -> laboratory frame, downhill to the right, y up. */
static void lab(const cli_TrackFigure *f, double x, double y, double *X, double *Y)
{
    const double c = cos(f->incline_rad), s = sin(f->incline_rad);
    *X = x * c + y * s;
    *Y = -x * s + y * c;
}

static void write_data(FILE *gp, const cli_TrackFigure *f)
{
    const cli_Track *t = f->track;
    double xmin = INFINITY, xmax = -INFINITY;
    fig_block_begin(gp, "frames");
    fputs("# t_s X_lab_m Y_lab_m height_mm dx_mm dy_mm across_mm (the mark's residual across its radius)\n", gp);
    for (long i = 0; i < f->count; ++i) {
        const long j = f->first + i;
        double X, Y;
        lab(f, t->x_m[j], t->y_m[j], &X, &Y);
        const double dx = t->x_m[j] - f->sim_x[i], dy = t->y_m[j] - f->sim_y[i], th = t->theta_rad[j];
        const double across = f->mark_radius_m > 0.0 && isfinite(th)
                                  ? f->mark_radius_m * (th - f->sim_theta[i]) + dx * cos(th) - dy * sin(th)
                                  : NAN;
        fprintf(gp, "%.10g", t->t_s[j]);
        put(gp, X);
        put(gp, Y);
        put(gp, (t->y_m[j] - f->radius_m) * 1e3);
        put(gp, dx * 1e3);
        put(gp, dy * 1e3);
        put(gp, across * 1e3);
        fputc('\n', gp);
        xmin = fmin(xmin, t->x_m[j]);
        xmax = fmax(xmax, t->x_m[j]);
    }
    fig_block_end(gp);
    fig_block_begin(gp, "model");
    fputs("# t_s X_lab_m Y_lab_m height_mm\n", gp);
    for (long i = 0; i < f->path_n; ++i) {
        double X, Y;
        lab(f, f->path_x[i], f->path_y[i], &X, &Y);
        fprintf(gp, "%.10g", f->path_t[i]);
        put(gp, X);
        put(gp, Y);
        put(gp, (f->path_y[i] - f->radius_m) * 1e3);
        fputc('\n', gp);
        xmin = fmin(xmin, f->path_x[i]);
        xmax = fmax(xmax, f->path_x[i]);
    }
    fig_block_end(gp);
    /* The incline's surface under the frames (the centre is r above it). */
    fig_block_begin(gp, "surface");
    double X, Y;
    lab(f, xmin - f->radius_m, 0.0, &X, &Y);
    fprintf(gp, "%.10g %.10g\n", X, Y);
    lab(f, xmax + f->radius_m, 0.0, &X, &Y);
    fprintf(gp, "%.10g %.10g\n", X, Y);
    fig_block_end(gp);
}

static void write_panels(FILE *gp, const cli_TrackFigure *f)
{
    fputs("\nset multiplot layout 3,1 title ", gp);
    fig_quote(gp, f->title);
    fputs(" font F_TITLE\n", gp);
    fig_panel_begin(gp, "the path in the laboratory frame, to scale");
    fputs("set title 'Tracked centre over the model path (laboratory frame, to scale)'\n"
          "set xlabel 'horizontal (m)'\nset ylabel 'height (m)'\nset size ratio -1\n"
          "plot $surface u 1:2 w l lc rgb C_GREY lw 3 t 'incline surface', \\\n"
          "     $model u 2:3 w l lc rgb C_BLUE lw LW t 'model: centre', \\\n"
          "     $frames u 2:3 w p pt 6 ps 0.9*PS lc rgb C_RED t 'tracked centre'\n",
          gp);
    fig_panel_begin(gp, "the centre's height above the surface");
    fprintf(gp,
            "set title 'Centre above the surface (hops show)'\nset xlabel 't (s)'\nset ylabel 'height above contact (mm)'\n"
            "plot $model u 1:4 w l lc rgb C_BLUE lw LW t 'model', \\\n"
            "     $frames u 1:4 w p pt 6 ps 0.9*PS lc rgb C_RED t 'tracked', \\\n"
            "     %.10g w l dt 2 lc rgb C_GREY lw 2 t 'hop threshold'\n",
            f->hop_threshold_m * 1e3);
    fig_panel_begin(gp, "residuals");
    fputs("set title 'Residuals: tracked minus model'\nset xlabel 't (s)'\nset ylabel 'residual (mm)'\n"
          "plot $frames u 1:5 w p pt 7 ps 0.6*PS lc rgb C_BLUE t 'centre, along the incline', \\\n"
          "     $frames u 1:6 w p pt 5 ps 0.6*PS lc rgb C_ORANGE t 'centre, across the incline'",
          gp);
    if (f->mark_radius_m > 0.0)
        fputs(", \\\n     $frames u 1:7 w p pt 9 ps 0.6*PS lc rgb C_GREEN t 'mark, across its radius (angle)'", gp);
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
