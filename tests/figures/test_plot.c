/* jumpcyl plot end to end (argv[1] is the built tool): every kind gives a
 * valid file of its format; the data written for a figure is the library's
 * numbers (read back and compared with the library called here); bad input
 * and a missing gnuplot give a message and a non-zero exit, and no file. */
#include "fig_common.h"

#include <gsl/gsl_errno.h>
#include <jumpcyl/jumpcyl.h>

#define PI 3.14159265358979323846
/* Data files hold 10 significant digits. */
#define DATA_REL 2e-9

static const char *cli;
static char dir[1024];

/* Reads the next data row of up to max numbers ("NaN" allowed); the count,
 * 0 at the end. Comment lines are skipped. */
static int read_row(FILE *f, double *v, int max)
{
    char line[4096];
    while (fgets(line, sizeof line, f)) {
        if (line[0] == '#' || line[0] == '\n') continue;
        int n = 0;
        char *s = line, *end;
        while (n < max) {
            const double x = strtod(s, &end);
            if (end == s) break;
            v[n++] = x;
            s = end;
        }
        return n;
    }
    return 0;
}

/* rel or abs closeness, NaN matching NaN. */
static int close_to(double a, double b, double rel, double abs_tol)
{
    if (isnan(a) || isnan(b)) return isnan(a) && isnan(b);
    return fabs(a - b) <= fmax(abs_tol, rel * fmax(fabs(a), fabs(b)));
}

static int init_model(jc_Model *m, double incline_deg)
{
    char err[256];
    jc_Setup s = jc_paper_setup();
    s.incline_rad = incline_deg * PI / 180;
    ENSURE_OK(jc_model_init(m, &s, err, sizeof err), err);
    return 0;
}

static int plot_ok(const char *args)
{
    cli_result r = cli_run_line(cli, NULL, args);
    const int ok = r.status == 0;
    if (!ok) fprintf(stderr, "'%s': status %d, stderr: %s\n", args, r.status, r.err ? r.err : "?");
    cli_result_free(&r);
    return ok;
}

/* plot with opts and --keep-script to stem.png in the scratch directory; the
 * kept script's path (stem.gp) and the library's model at incline_deg. */
static int plot_kept(const char *stem, const char *opts, double incline_deg, jc_Model *m, char *script, size_t len)
{
    char args[2400], out[1100];
    snprintf(out, sizeof out, "%s/%s.png", dir, stem);
    snprintf(args, sizeof args, "plot %s --keep-script --output '%s'", opts, out);
    ENSURE(plot_ok(args));
    snprintf(script, len, "%s/%s.gp", dir, stem);
    return init_model(m, incline_deg);
}

static int test_every_kind_png(void)
{
    static const char *kinds[] = {"paper-criterion", "forces", "gap", "path", "energy", "trajectory", "overview"};
    for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; ++i) {
        char args[2048], out[1100];
        snprintf(out, sizeof out, "%s/%s.png", dir, kinds[i]);
        snprintf(args, sizeof args, "plot --incline 45 --what %s --output '%s'", kinds[i], out);
        ENSURE(plot_ok(args));
        int w, h;
        ENSURE_MSG(fig_png_size(out, &w, &h) == 0, "%s is not a PNG", out);
        const int pages = strcmp(kinds[i], "overview") == 0 || strcmp(kinds[i], "trajectory") == 0 ? 2 : 1;
        ENSURE_MSG(w == 1200 * pages && h == 750 * pages, "%s: %dx%d", out, w, h);
        const long size = fig_file_size(out);
        ENSURE_MSG(size > 20000 && size < 5000000, "%s: %ld bytes", out, size);
    }
    return 0;
}

static int test_svg_and_pdf(void)
{
    char args[2048], out[1100];
    snprintf(out, sizeof out, "%s/forces.svg", dir);
    snprintf(args, sizeof args, "plot --incline 30 --what forces --output '%s'", out);
    ENSURE(plot_ok(args));
    unsigned char head[6];
    ENSURE(fig_head(out, head, 5) == 0);
    ENSURE(memcmp(head, "<?xml", 5) == 0 || memcmp(head, "<svg", 4) == 0);
    long size = fig_file_size(out);
    ENSURE_MSG(size > 10000 && size < 10000000, "%ld bytes", size);
    FILE *f = fopen(out, "r");
    ENSURE(f);
    char *text = cli_run_read_all(f);
    fclose(f);
    const int complete = text && strstr(text, "</svg>") != NULL;
    free(text);
    ENSURE(complete);

    snprintf(out, sizeof out, "%s/criterion.pdf", dir);
    snprintf(args, sizeof args, "plot --incline 15 --what paper-criterion --output '%s'", out);
    ENSURE(plot_ok(args));
    ENSURE(fig_head(out, head, 5) == 0 && memcmp(head, "%PDF-", 5) == 0);
    size = fig_file_size(out);
    ENSURE_MSG(size > 5000 && size < 5000000, "%ld bytes", size);
    return 0;
}

/* Both sides of Eq. 9 and the exact condition, row by row, against the library. */
static int check_criterion_rows(const jc_Model *m, const char *path)
{
    FILE *f = fopen(path, "r");
    ENSURE_MSG(f, "%s missing", path);
    double v[6];
    int rows = 0, exact_rows = 0, n;
    while ((n = read_row(f, v, 6)) > 0) {
        ENSURE(n == 6);
        const double th = v[0], g = m->setup.gravity_mps2, d = m->body.cm_offset_m;
        ENSURE(close_to(v[1], m->body.radius_m * th * 100, DATA_REL, 1e-12));
        ENSURE_MSG(close_to(v[2], jc_paper_lhs(m, th), DATA_REL, 1e-12), "lhs at %.17g", th);
        ENSURE_MSG(close_to(v[3], jc_paper_rhs(m, th), DATA_REL, 1e-12), "rhs at %.17g", th);
        ++rows;
        if (isnan(v[4])) continue; /* past the rolling path's end */
        jc_RollingState rs;
        char err[256];
        ENSURE_OK(jc_rolling_state(m, th, &rs, err, sizeof err), err);
        ENSURE(close_to(v[4], rs.omega_radps * rs.omega_radps / g, DATA_REL, 1e-12));
        /* The plotted threshold is the exact N = 0 condition: the library's own
         * N equals M d cos(th) g (rhs - lhs). */
        const double n_from_curves = m->body.mass_kg * d * cos(th) * g * (v[5] - v[4]);
        ENSURE_MSG(fabs(n_from_curves - rs.normal_N) <= 1e-6 * m->body.mass_kg * g * (1 + fabs(v[5]) * d),
                   "N %.9g vs %.9g at %.6g", n_from_curves, rs.normal_N, th);
        exact_rows += isfinite(v[5]);
    }
    fclose(f);
    ENSURE_MSG(rows > 1000 && exact_rows > 1000, "%d rows, %d exact", rows, exact_rows);
    return 0;
}

static int check_roots(const jc_Model *m, const char *path)
{
    jc_PaperResult pr;
    char err[256];
    ENSURE_OK(jc_paper_solve(m, &pr, err, sizeof err), err);
    FILE *f = fopen(path, "r");
    ENSURE_MSG(f, "%s missing", path);
    double v[4];
    int i = 0;
    while (read_row(f, v, 4) == 4) {
        ENSURE(i < pr.root_count);
        ENSURE_NEAR(v[0], pr.theta_rad[i], 1e-10);
        ENSURE(close_to(v[1], pr.x_m[i] * 100, DATA_REL, 1e-12));
        ENSURE((int)v[3] == (i == pr.first));
        ++i;
    }
    fclose(f);
    ENSURE_MSG(i == pr.root_count, "%d roots written, %d found", i, pr.root_count);
    return 0;
}

/* The printed angle the script marks is the one of the paper's table. */
static int check_printed(const char *script, double incline_deg)
{
    FILE *f = fopen(script, "r");
    ENSURE(f);
    char *text = cli_run_read_all(f);
    fclose(f);
    ENSURE(text);
    const char *p = strstr(text, "PRINTED_THETA = ");
    const double printed = p ? strtod(p + 16, NULL) : NAN;
    free(text);
    const jc_PaperTableRow *rows;
    const int n = jc_paper_table(&rows);
    for (int i = 0; i < n; ++i)
        if (rows[i].incline_deg == incline_deg) ENSURE_NEAR(printed, rows[i].printed_theta_rad, 1e-12);
    return 0;
}

/* The data block $name of a kept script, copied to its own file (the
 * script holds its data; it reads no file). */
static int extract_block(const char *script, const char *name, const char *out)
{
    FILE *in = fopen(script, "r");
    if (!in) return -1;
    FILE *o = fopen(out, "w");
    if (!o) {
        fclose(in);
        return -1;
    }
    char line[4096], start[64];
    snprintf(start, sizeof start, "$%s << EOD\n", name);
    int inside = 0, found = 0;
    while (fgets(line, sizeof line, in)) {
        if (inside && strcmp(line, "EOD\n") == 0) break;
        if (inside) fputs(line, o);
        if (!inside && strcmp(line, start) == 0) inside = found = 1;
    }
    fclose(in);
    fclose(o);
    return found ? 0 : -1;
}

static int test_criterion_data(void)
{
    char script[1200], path[1200];
    jc_Model m;
    if (plot_kept("c30", "--what paper-criterion", 30, &m, script, sizeof script)) return 1;
    snprintf(path, sizeof path, "%s/c30-criterion.dat", dir);
    ENSURE(extract_block(script, "criterion", path) == 0);
    if (check_criterion_rows(&m, path)) return 1;
    snprintf(path, sizeof path, "%s/c30-roots.dat", dir);
    ENSURE(extract_block(script, "roots", path) == 0);
    if (check_roots(&m, path)) return 1;
    return check_printed(script, 30);
}

/* The sample spacing the plot chose, from the run file's header. */
static double header_dt(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f) return NAN;
    char line[1024];
    double dt = NAN;
    while (fgets(line, sizeof line, f) && line[0] == '#') {
        const char *p = strstr(line, "sample_dt_s = ");
        if (p) dt = strtod(p + 14, NULL);
    }
    fclose(f);
    return dt;
}

/* A check of a data file against the run, the file open (check_file opens and closes it). */
typedef int (*data_check)(const jc_Model *m, const jc_Run *run, FILE *f);

static int check_file(const char *path, data_check check, const jc_Model *m, const jc_Run *run)
{
    FILE *f = fopen(path, "r");
    ENSURE_MSG(f, "%s missing", path);
    const int bad = check(m, run, f);
    fclose(f);
    return bad;
}

static int check_run_rows(const jc_Model *m, const jc_Run *run, FILE *f)
{
    const double weight = m->body.mass_kg * m->setup.gravity_mps2 * m->cos_incline;
    double v[16];
    int i = 0, n;
    while ((n = read_row(f, v, 16)) > 0) {
        ENSURE(n == 15 && i < run->sample_count);
        const jc_Sample *p = &run->samples[i++];
        const double ratio = p->mode != JC_MODE_FLIGHT && p->normal_N > 1e-9 * m->body.mass_kg * m->setup.gravity_mps2
                                 ? fabs(p->friction_N) / p->normal_N : NAN;
        const double sum = p->kinetic_J + p->potential_J + p->friction_loss_J + p->impact_loss_J + p->air_loss_J +
                           p->rolling_resistance_loss_J;
        const double want[] = {p->state.t_s, p->state.x_m * 100, (double)p->mode, p->normal_N / weight, ratio,
                               p->gap_m * 1e3, hypot(p->state.vx_mps, p->state.vy_mps), p->kinetic_J, p->potential_J,
                               p->friction_loss_J, p->impact_loss_J, sum, p->normal_N, p->friction_N};
        for (int k = 0; k < 14; ++k)
            ENSURE_MSG(close_to(v[k], want[k], DATA_REL, 1e-12), "row %d column %d: %.12g vs %.12g", i, k + 1, v[k],
                       want[k]);
    }
    ENSURE_MSG(i == run->sample_count, "%d rows for %d samples", i, run->sample_count);
    return 0;
}

static int check_events(const jc_Model *m, const jc_Run *run, FILE *f)
{
    (void)m;
    char line[1024];
    int i = 0;
    while (fgets(line, sizeof line, f)) {
        if (line[0] == '#') continue;
        double x, t;
        char kind[64];
        ENSURE(sscanf(line, "%lf %lf %63s", &x, &t, kind) == 3 && i < run->event_count);
        const jc_Event *e = &run->events[i++];
        ENSURE_MSG(strcmp(kind, jc_event_name(e->kind)) == 0, "event %d: %s vs %s", i, kind, jc_event_name(e->kind));
        ENSURE(close_to(x, e->state.x_m * 100, DATA_REL, 1e-12) && close_to(t, e->state.t_s, 1e-11, 1e-12));
    }
    ENSURE_MSG(i == run->event_count, "%d events written, %d in the run", i, run->event_count);
    return 0;
}

static int check_hops(const jc_Model *m, const jc_Run *run, FILE *f)
{
    (void)m;
    double v[5];
    int e = 0, hops = 0;
    while (read_row(f, v, 5) == 5) {
        while (e < run->event_count && !(run->events[e].kind == JC_EVENT_LIFTOFF ||
                                         (run->events[e].kind == JC_EVENT_BOUNCE && run->events[e].mode_after == JC_MODE_FLIGHT)))
            ++e;
        ENSURE(e < run->event_count);
        ENSURE(close_to(v[2], run->events[e].state.t_s, 1e-11, 1e-12));
        ENSURE(close_to(v[3], run->events[e].hop_height_m * 1e3, DATA_REL, 1e-15));
        ++e;
        ++hops;
    }
    int flights = 0;
    for (int i = 0; i < run->event_count; ++i)
        flights += run->events[i].kind == JC_EVENT_LIFTOFF ||
                   (run->events[i].kind == JC_EVENT_BOUNCE && run->events[i].mode_after == JC_MODE_FLIGHT);
    ENSURE_MSG(hops == flights && hops > 0, "%d hops written, %d flights", hops, flights);
    return 0;
}

static int test_run_data(void)
{
    char script[1200], path[1200], events[1200], hops[1200];
    jc_Model m;
    if (plot_kept("f45", "--incline 45 --what overview", 45, &m, script, sizeof script)) return 1;
    snprintf(path, sizeof path, "%s/f45-run.dat", dir);
    snprintf(events, sizeof events, "%s/f45-events.dat", dir);
    snprintf(hops, sizeof hops, "%s/f45-hops.dat", dir);
    ENSURE(extract_block(script, "run", path) == 0 && extract_block(script, "events", events) == 0 &&
           extract_block(script, "hops", hops) == 0);
    jc_SimOptions o = jc_default_sim_options();
    o.sample_dt_s = header_dt(path);
    ENSURE(o.sample_dt_s > 0 && o.sample_dt_s < 1e-3);
    jc_Run run;
    char err[256];
    const int st = jc_simulate(&m, &o, &run, err, sizeof err);
    int bad = st != JC_OK;
    if (bad) fprintf(stderr, "jc_simulate: %s\n", err);
    if (!bad) bad = check_file(path, check_run_rows, &m, &run);
    if (!bad) bad = check_file(events, check_events, &m, &run);
    if (!bad) bad = check_file(hops, check_hops, &m, &run);
    jc_run_free(&run);
    return bad;
}


/* Geometry tolerance of the trajectory's outlines (m): the data hold 10
 * significant digits of cm, about 1e-10 m at a few metres. */
#define GEOMETRY_TOL_M 1e-6

/* The outline drawn at the first lift-off, from the $outlines block: its
 * contact x, centre (picture cm) and radius (cm). */
static int first_liftoff_outline(const char *path, double *contact_cm, double *X, double *Y, double *r_cm)
{
    FILE *f = fopen(path, "r");
    ENSURE(f);
    char line[1024], kind[64];
    double v[9];
    int found = 0;
    while (!found && fgets(line, sizeof line, f)) {
        if (line[0] == '#') continue;
        ENSURE(sscanf(line, "%lf %lf %lf %lf %lf %lf %lf %lf %lf %63s", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5],
                      &v[6], &v[7], &v[8], kind) == 10);
        found = strcmp(kind, "liftoff") == 0;
    }
    fclose(f);
    ENSURE_MSG(found, "no lift-off outline in %s", path);
    *contact_cm = v[0];
    *X = v[1];
    *Y = v[2];
    *r_cm = v[3];
    return 0;
}

/* Lines of the script that start with prefix. */
static int count_lines(const char *script, const char *prefix)
{
    FILE *f = fopen(script, "r");
    if (!f) return -1;
    char line[4096];
    int n = 0;
    while (fgets(line, sizeof line, f)) n += strncmp(line, prefix, strlen(prefix)) == 0;
    fclose(f);
    return n;
}

/* The outline drawn at the first lift-off touches the incline where the
 * run says: its centre is r from the incline line (picture: through the
 * origin along (cos a, -sin a)) and the foot of the perpendicular is the
 * lift-off's contact x; and every panel has equal axes. */
static int test_trajectory_geometry(void)
{
    char args[2048], out[1100], script[1200], path[1200];
    snprintf(out, sizeof out, "%s/t45.png", dir);
    snprintf(args, sizeof args, "plot --incline 45 --what trajectory --keep-script --output '%s'", out);
    ENSURE(plot_ok(args));
    int w, h;
    ENSURE(fig_png_size(out, &w, &h) == 0 && w == 2400 && h == 1500);
    snprintf(script, sizeof script, "%s/t45.gp", dir);
    snprintf(path, sizeof path, "%s/t45-outlines.dat", dir);
    ENSURE(extract_block(script, "outlines", path) == 0);
    double contact_cm, X, Y, r_cm;
    if (first_liftoff_outline(path, &contact_cm, &X, &Y, &r_cm)) return 1;
    jc_Model m;
    if (init_model(&m, 45)) return 1;
    jc_Run run;
    char err[256];
    const jc_SimOptions o = jc_default_sim_options();
    const int st = jc_simulate(&m, &o, &run, err, sizeof err);
    jc_RunSummary sum;
    if (st == JC_OK) jc_run_summarize(&run, &sum);
    jc_run_free(&run);
    ENSURE_MSG(st == JC_OK && sum.first_liftoff >= 0, "%s", err);
    const double a = m.setup.incline_rad, x_liftoff_m = sum.first_liftoff_state.x_m;
    const double distance_m = (X * sin(a) + Y * cos(a)) / 100, foot_m = (X * cos(a) - Y * sin(a)) / 100;
    ENSURE_MSG(fabs(r_cm / 100 - m.body.radius_m) <= GEOMETRY_TOL_M, "radius %.9g cm", r_cm);
    ENSURE_MSG(fabs(distance_m - m.body.radius_m) <= GEOMETRY_TOL_M, "centre %.9g m from the incline, r = %.9g m",
               distance_m, m.body.radius_m);
    ENSURE_MSG(fabs(foot_m - x_liftoff_m) <= GEOMETRY_TOL_M, "foot at x = %.9g m, lift-off at %.9g m", foot_m,
               x_liftoff_m);
    ENSURE_MSG(fabs(contact_cm / 100 - x_liftoff_m) <= GEOMETRY_TOL_M, "contact x %.9g cm", contact_cm);
    /* Equal axes: one 'set size ratio -1' for each panel's plot. */
    const int plots = count_lines(script, "plot "), ratios = count_lines(script, "set size ratio -1");
    ENSURE_MSG(plots == 3 && ratios == plots, "%d plots, %d 'set size ratio -1'", plots, ratios);
    return 0;
}

/* The xrange of the first panel that sets one after the line holding
 * marker; NaN if none. */
static double xrange_after(const char *script, const char *marker, double *hi)
{
    FILE *f = fopen(script, "r");
    if (!f) return NAN;
    char line[4096];
    int on = 0;
    double lo = NAN;
    while (fgets(line, sizeof line, f) && isnan(lo)) {
        if (strstr(line, marker)) on = 1;
        if (on && sscanf(line, "set xrange [%lf:%lf]", &lo, hi) != 2) lo = NAN;
    }
    fclose(f);
    return lo;
}

/* The first slip's distance down the incline (cm) on the paper's cylinder
 * at incline_deg, from the library's run; NaN if none. */
static double first_slip_cm(double incline_deg)
{
    jc_Model m;
    if (init_model(&m, incline_deg)) return NAN;
    jc_Run run;
    char err[256];
    const jc_SimOptions o = jc_default_sim_options();
    double x = NAN;
    if (jc_simulate(&m, &o, &run, err, sizeof err) == JC_OK)
        for (int i = 0; i < run.event_count && isnan(x); ++i)
            if (run.events[i].kind == JC_EVENT_SLIP) x = run.events[i].state.x_m * 100;
    jc_run_free(&run);
    return x;
}

/* The overview zooms its run panels from before the first slip (15
 * degrees: slip at 125 cm, lift-off at 181 cm, hops to the ramp's end) and
 * says so; at 45 degrees (slip at 13 cm) that would be the whole run, which
 * it shows unzoomed; without a lift-off it shows the whole run. */
static int test_overview_zoom(void)
{
    char args[2048], out[1100], script[1200];
    snprintf(out, sizeof out, "%s/o15.png", dir);
    snprintf(args, sizeof args, "plot --incline 15 --what overview --keep-script --output '%s'", out);
    ENSURE(plot_ok(args));
    snprintf(script, sizeof script, "%s/o15.gp", dir);
    double hi = NAN;
    const double lo = xrange_after(script, "panel: forces", &hi);
    const double slip = first_slip_cm(15), r_cm = 10.0;
    /* 3 r before the first slip (or before a near-miss of N = 0 just before it) */
    ENSURE_MSG(lo <= slip - 3 * r_cm + 1e-6 && lo > slip - 3 * r_cm - 10 && hi > 300, "forces xrange [%g:%g], slip at %g cm",
               lo, hi, slip);
    ENSURE(count_lines(script, "set multiplot") == 1);
    FILE *f = fopen(script, "r");
    ENSURE(f);
    char line[4096];
    int said = 0;
    while (fgets(line, sizeof line, f)) said += strstr(line, "set multiplot") && strstr(line, "zoomed to x =");
    fclose(f);
    ENSURE_MSG(said == 1, "the page title does not say it is zoomed");
    const char *whole[] = {"5", "45"}; /* no lift-off; the first slip near the start */
    for (int k = 0; k < 2; ++k) {
        snprintf(out, sizeof out, "%s/o%s.png", dir, whole[k]);
        snprintf(args, sizeof args, "plot --incline %s --what overview --keep-script --output '%s'", whole[k], out);
        ENSURE(plot_ok(args));
        snprintf(script, sizeof script, "%s/o%s.gp", dir, whole[k]);
        const double lo_w = xrange_after(script, "panel: forces", &hi);
        ENSURE_MSG(lo_w == 0 && hi > 300, "%s deg: xrange [%g:%g], not the whole run", whole[k], lo_w, hi);
    }
    ENSURE_MSG(first_slip_cm(45) < 30, "45 deg: the first slip at %g cm", first_slip_cm(45));
    return 0;
}

/* The last row of a kept script's $run block: its time (s). */
static double last_run_t(const char *script, const char *tag)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/%s-run.dat", dir, tag);
    if (extract_block(script, "run", path) != 0) return NAN;
    FILE *f = fopen(path, "r");
    if (!f) return NAN;
    double v[16], t = NAN;
    while (read_row(f, v, 16) > 0) t = v[0];
    fclose(f);
    return t;
}

/* Whether a line of the script holds both needles. */
static int script_says(const char *script, const char *a, const char *b)
{
    FILE *f = fopen(script, "r");
    if (!f) return 0;
    char line[4096];
    int said = 0;
    while (fgets(line, sizeof line, f)) said |= strstr(line, a) && (!b || strstr(line, b));
    fclose(f);
    return said;
}

/* The rocking hoop never lifts off and rocks until the 60 s limit: the run
 * panels end where its losses first reach 99 % of their value at 60 s
 * (found here on the library's own run, sampled every millisecond) and say
 * so; --t-max shows the whole run. Its many slips and sticks are labelled
 * as cycles. */
static int test_rocking_cut(void)
{
    jc_Setup s;
    jc_Model m;
    char err[256];
    ENSURE_OK(jc_preset_setup("rocking-hoop", &s, err, sizeof err), err);
    ENSURE_OK(jc_model_init(&m, &s, err, sizeof err), err);
    jc_SimOptions o = jc_default_sim_options();
    o.sample_dt_s = 1e-3;
    jc_Run run;
    ENSURE_OK(jc_simulate(&m, &o, &run, err, sizeof err), err);
    const jc_Sample *end = &run.samples[run.sample_count - 1];
    const double total = end->friction_loss_J + end->impact_loss_J;
    double t99 = NAN;
    for (int i = 0; i < run.sample_count && isnan(t99); ++i)
        if (run.samples[i].friction_loss_J + run.samples[i].impact_loss_J >= 0.99 * total) t99 = run.samples[i].state.t_s;
    int flies = 0;
    for (int i = 0; i < run.event_count; ++i) flies |= run.events[i].kind == JC_EVENT_LIFTOFF;
    ENSURE_MSG(run.termination == JC_END_TIME_LIMIT && !flies, "the rocking hoop lifted off or ended before the limit");
    jc_run_free(&run);
    char args[2048], out[1100], script[1200];
    snprintf(out, sizeof out, "%s/rock.png", dir);
    snprintf(args, sizeof args, "plot --preset rocking-hoop --what forces --keep-script --output '%s'", out);
    ENSURE(plot_ok(args));
    snprintf(script, sizeof script, "%s/rock.gp", dir);
    /* The plot finds it on samples 60 s / 6000 apart. */
    const double shown = last_run_t(script, "rock");
    ENSURE_MSG(t99 > 5 && t99 < 30 && fabs(shown - t99) <= 0.011, "shown to %g s, losses at 99 %% at %g s", shown, t99);
    ENSURE_MSG(script_says(script, "set title", "where the losses reach 99 % of their total; it rocks on to 60 s"),
               "the title does not say what is cut");
    ENSURE_MSG(script_says(script, "stick–slip cycles", NULL), "no label in cycles");
    ENSURE_MSG(!script_says(script, "stick ×", NULL) && !script_says(script, "slip ×", NULL), "a label counts kinds");
    snprintf(args, sizeof args, "plot --preset rocking-hoop --what forces --t-max 60 --keep-script --output '%s'", out);
    ENSURE(plot_ok(args));
    ENSURE_NEAR(last_run_t(script, "rock"), 60.0, 1e-9);
    ENSURE_MSG(!script_says(script, "set title", "shown to t ="), "--t-max 60 still says it is cut");
    return 0;
}

/* The hoops' paper-criterion: the paper's kinetic side peaks at 4400 1/m
 * where its threshold is negative (cos th < 0, the mass at the bottom);
 * the axis is sized to it where the threshold is positive (from
 * jc_paper_lhs here), and those peaks run off the top. */
static int test_criterion_clip(void)
{
    jc_Setup s;
    jc_Model m;
    char err[256];
    ENSURE_OK(jc_preset_setup("rocking-hoop", &s, err, sizeof err), err);
    ENSURE_OK(jc_model_init(&m, &s, err, sizeof err), err);
    double peak = 0, crossable = 0;
    const double end = s.ramp_length_m / m.body.radius_m;
    for (int i = 0; i <= 20000; ++i) {
        const double th = end * i / 20000, y = jc_paper_lhs(&m, th);
        if (!isfinite(y)) continue;
        peak = fmax(peak, y);
        if (cos(th) > 0) crossable = fmax(crossable, y);
    }
    char args[2048], out[1100], script[1200];
    snprintf(out, sizeof out, "%s/rockc.png", dir);
    snprintf(args, sizeof args, "plot --preset rocking-hoop --what paper-criterion --keep-script --output '%s'", out);
    ENSURE(plot_ok(args));
    snprintf(script, sizeof script, "%s/rockc.gp", dir);
    FILE *f = fopen(script, "r");
    ENSURE(f);
    char line[4096];
    double ymax = NAN, lo;
    while (fgets(line, sizeof line, f))
        if (sscanf(line, "set yrange [%lf:%lf]", &lo, &ymax) == 2) break;
    fclose(f);
    ENSURE_MSG(peak > 10 * ymax && ymax >= 1.15 * crossable, "yrange top %g: peak %g, %g where cos th > 0", ymax, peak,
               crossable);
    ENSURE(script_says(script, "set title", "run off the top"));
    return 0;
}

/* paper-criterion at 30 degrees: an inset whose view holds the paper's
 * first two crossings (jc_paper_solve: 6.12 and 6.87 rad), narrower than a
 * tenth of the main panel's axis. */
static int test_criterion_inset(void)
{
    char args[2048], out[1100], script[1200];
    snprintf(out, sizeof out, "%s/ci30.png", dir);
    snprintf(args, sizeof args, "plot --incline 30 --what paper-criterion --keep-script --output '%s'", out);
    ENSURE(plot_ok(args));
    snprintf(script, sizeof script, "%s/ci30.gp", dir);
    double main_hi = NAN, hi = NAN;
    const double main_lo = xrange_after(script, "panel: paper-criterion (", &main_hi);
    const double lo = xrange_after(script, "panel: paper-criterion inset", &hi);
    jc_Model m;
    if (init_model(&m, 30)) return 1;
    jc_PaperResult pr;
    char err[256];
    ENSURE_OK(jc_paper_solve(&m, &pr, err, sizeof err), err);
    ENSURE(pr.first >= 0 && pr.first + 1 < pr.root_count);
    const double a = pr.theta_rad[pr.first], b = pr.theta_rad[pr.first + 1];
    ENSURE_MSG(lo < a && hi > b && hi - lo < 0.1 * (main_hi - main_lo), "inset [%g:%g], crossings %g, %g, main [%g:%g]", lo,
               hi, a, b, main_lo, main_hi);
    return 0;
}

/* The kept script renders the figure again by hand, from its directory. */
static int test_kept_script_reruns(void)
{
    char out[1100], cmd[2400];
    snprintf(out, sizeof out, "%s/c30.png", dir);
    ENSURE(cli_file_exists(out));
    remove(out);
    snprintf(cmd, sizeof cmd, "cd '%s' && gnuplot c30.gp 2>/dev/null", dir);
    ENSURE(system(cmd) == 0);
    int w, h;
    ENSURE(fig_png_size(out, &w, &h) == 0 && w == 1200 && h == 750);
    return 0;
}

/* plot with opts and the output file in the scratch directory: exit 2, a
 * one-line message naming the value, and no file. */
static int usage_error(const char *opts, const char *file, const char *needle)
{
    char args[2400], out[1100];
    snprintf(out, sizeof out, "%s/%s", dir, file);
    snprintf(args, sizeof args, "plot %s --output '%s'", opts, out);
    cli_result r = cli_run_line(cli, NULL, args);
    const int ok = r.status == 2 && r.err && strstr(r.err, needle) && strchr(r.err, '\n') == r.err + strlen(r.err) - 1;
    if (!ok) fprintf(stderr, "'%s': status %d, stderr: %s\n", args, r.status, r.err ? r.err : "?");
    cli_result_free(&r);
    ENSURE(ok);
    ENSURE_MSG(!cli_file_exists(out), "%s was written", out);
    return 0;
}

static int test_bad_input(void)
{
    if (usage_error("--what sideways", "bad.png", "'sideways'") || usage_error("--what path", "bad.jpg", ".jpg") ||
        usage_error("--what path", "bad", "no extension") || usage_error("--what path --incline 95", "bad.png", "95"))
        return 1;
    /* An output directory that does not exist: exit 1 naming the path. */
    char args[2048], out[1100];
    snprintf(out, sizeof out, "%s/no/such/dir/x.png", dir);
    snprintf(args, sizeof args, "plot --what path --output '%s'", out);
    cli_result r = cli_run_line(cli, NULL, args);
    const int ok = r.status == 1 && r.err && strstr(r.err, out);
    cli_result_free(&r);
    ENSURE(ok);
    return 0;
}

static int test_missing_gnuplot(void)
{
    char args[2048], out[1100];
    snprintf(out, sizeof out, "%s/nognuplot.png", dir);
    snprintf(args, sizeof args, "plot --what energy --output '%s'", out);
    return fig_without_tools(cli, dir, args, out, "gnuplot", "not found", 0);
}

/* Nothing but the figure and the script (which holds the data) is left (no temporaries). */
static int test_no_leftovers(void)
{
    char sub[1100], args[2048], out[1200];
    snprintf(sub, sizeof sub, "%s/clean", dir);
    ENSURE(mkdir(sub, 0755) == 0);
    snprintf(out, sizeof out, "%s/p.png", sub);
    snprintf(args, sizeof args, "plot --what path --output '%s'", out);
    ENSURE(plot_ok(args));
    ENSURE_MSG(fig_count_entries(sub) == 1, "%d files", fig_count_entries(sub));
    snprintf(args, sizeof args, "plot --what path --keep-script --output '%s'", out);
    ENSURE(plot_ok(args));
    ENSURE_MSG(fig_count_entries(sub) == 2, "%d files (png, gp)", fig_count_entries(sub));
    return 0;
}

int main(int argc, char **argv)
{
    const int rc = fig_main_begin(argc, argv, "plot", &cli, dir, sizeof dir);
    if (rc != 0) return rc;
    RUN_TEST(test_every_kind_png);
    RUN_TEST(test_svg_and_pdf);
    RUN_TEST(test_criterion_data);
    RUN_TEST(test_run_data);
    RUN_TEST(test_trajectory_geometry);
    RUN_TEST(test_overview_zoom);
    RUN_TEST(test_criterion_inset);
    RUN_TEST(test_rocking_cut);
    RUN_TEST(test_criterion_clip);
    RUN_TEST(test_kept_script_reruns);
    RUN_TEST(test_bad_input);
    RUN_TEST(test_missing_gnuplot);
    RUN_TEST(test_no_leftovers);
    fig_main_end(dir);
    TEST_MAIN_END();
}
