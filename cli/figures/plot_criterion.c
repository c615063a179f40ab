/* paper-criterion: the paper's Figures 2-4 for any setup. Both sides of its
 * Eq. 9 against the rotation angle, every intersection, the jump angle its
 * Table 1 prints, and the exact rolling model's N = 0 condition written in
 * the same form, w^2/g = (cos a - d sin th th''/g) / (d cos th), so that the
 * two criteria can be compared curve by curve. */
#include "figures.h"

#include <math.h>
#include <string.h>

/* Enough points that the steep branches of the threshold near cos th = 0 are
 * drawn smoothly over the whole ramp (about 100 per turn on the paper's). */
#define CRIT_POINTS 4001
/* The first crossing is narrow (the panel gets an inset on it) when its
 * window to the next crossing is under this fraction of the axis, or it
 * lies under this fraction of the graph's height. */
#define INSET_NARROW_FRACTION 0.08
#define INSET_LOW_FRACTION 0.12
#define INSET_MIN_WIDTH_RAD 0.3
/* The kinetic side can peak far higher where the threshold is negative
 * (cos th < 0: no crossing there) than where it is positive: a hoop's
 * paper-model I_P nearly vanishes with the mass at the bottom. Past this
 * ratio the axis is sized to the kinetic side where a crossing can be,
 * and those peaks run off the top. */
#define CRIT_CLIP_RATIO 3.0

static void find_printed(fig_Data *d)
{
    d->printed_theta_rad = d->printed_x_m = NAN;
    const jc_PaperTableRow *row = cli_paper_row(&d->model->setup);
    if (!row) return;
    d->printed_theta_rad = row->printed_theta_rad;
    d->printed_x_m = row->printed_x_m;
}

/* Both sides of the exact N = 0 condition at th, NaN where the rolling path
 * from the setup's start does not go or the threshold is undefined. */
static void exact_sides(const fig_Data *d, double th, double *lhs, double *rhs)
{
    const jc_Model *m = d->model;
    *lhs = *rhs = NAN;
    const double lo = fmin(m->setup.theta0_rad, d->rolling.end_theta_rad);
    const double hi = fmax(m->setup.theta0_rad, d->rolling.end_theta_rad);
    jc_RollingState rs;
    char err[256];
    if (th < lo || th > hi || jc_rolling_state(m, th, &rs, err, sizeof err) != JC_OK) return;
    const double g = m->setup.gravity_mps2, dd = m->body.cm_offset_m;
    *lhs = rs.omega_radps * rs.omega_radps / g;
    const double den = dd * cos(th);
    if (den != 0.0) *rhs = (m->cos_incline - dd * sin(th) * rs.alpha_radps2 / g) / den;
}

/* Data files hold "NaN" for undefined values: gnuplot breaks lines there. */
static void put(FILE *f, double v)
{
    if (isfinite(v)) fprintf(f, " %.10g", v);
    else fputs(" NaN", f);
}

/* 1, 2 or 5 times a power of ten, near x: a tic step. */
static double nice_step(double x)
{
    const double p = pow(10.0, floor(log10(x))), m = x / p;
    return (m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0) * p;
}

static double theta_of(const fig_Data *d, int i) { return d->theta_max_rad * i / (CRIT_POINTS - 1); }

static int write_curves(fig_Data *d)
{
    FILE *f = d->gp;
    fig_block_begin(f, "criterion");
    const jc_Model *m = d->model;
    fprintf(f, "# jumpcyl plot --what paper-criterion: the paper's Eq. 9 and the exact N = 0 condition.\n"
                  "# paper_lhs, paper_rhs: jc_paper_lhs, jc_paper_rhs (the paper's model: d = %.6g m, from rest at theta = 0).\n"
                  "# exact_lhs = w^2/g, exact_rhs = (cos a - d sin(theta) theta''/g)/(d cos(theta)), from jc_rolling_state\n"
                  "#   (exact rolling model, d = %.6g m); N = 0 where they are equal. NaN: undefined or not reached.\n"
                  "# columns: theta_rad x_cm(r*theta) paper_lhs_per_m paper_rhs_per_m exact_lhs_per_m exact_rhs_per_m\n",
            m->paper_d_m, m->body.cm_offset_m);
    double ymax = 0.0, ymax_crossable = 0.0;
    for (int i = 0; i < CRIT_POINTS; ++i) {
        const double th = theta_of(d, i), pl = jc_paper_lhs(m, th), pr = jc_paper_rhs(m, th);
        double el, er;
        exact_sides(d, th, &el, &er);
        fprintf(f, "%.17g", th); /* exact: a reader can recompute at the same angle */
        put(f, m->body.radius_m * th * 100);
        put(f, pl);
        put(f, pr);
        put(f, el);
        put(f, er);
        fputc('\n', f);
        if (isfinite(pl)) ymax = fmax(ymax, pl);
        if (isfinite(el)) ymax = fmax(ymax, el);
        if (isfinite(pl) && pr > 0) ymax_crossable = fmax(ymax_crossable, pl);
        if (isfinite(el) && er > 0) ymax_crossable = fmax(ymax_crossable, el);
    }
    d->crit_clipped = ymax_crossable > 0 && ymax > CRIT_CLIP_RATIO * ymax_crossable;
    if (d->crit_clipped) ymax = ymax_crossable;
    /* Room above the kinetic side, and the threshold's minimum cos a / d well inside. */
    const double floor_y = m->cos_incline / m->paper_d_m;
    d->crit_ymax = fmax(1.15 * ymax, isfinite(floor_y) ? 2.5 * floor_y : 0.0);
    if (!(d->crit_ymax > 0)) d->crit_ymax = 1.0;
    fig_block_end(f);
    return EXIT_OK;
}

static int write_roots(const fig_Data *d)
{
    FILE *f = d->gp;
    fig_block_begin(f, "roots");
    fprintf(f, "# jumpcyl plot --what paper-criterion: every intersection of the two sides of the paper's\n"
                  "# Eq. 9 with cos(theta) > 0 (jc_paper_solve)%s; first = 1 marks the paper's prediction.\n"
                  "# columns: theta_rad x_cm paper_lhs_per_m first\n",
            d->paper.truncated ? ", the first ones only (more exist)" : "");
    for (int i = 0; i < d->paper.root_count; ++i)
        fprintf(f, "%.17g %.10g %.10g %d\n", d->paper.theta_rad[i], d->paper.x_m[i] * 100,
                jc_paper_lhs(d->model, d->paper.theta_rad[i]), i == d->paper.first);
    fig_block_end(f);
    return EXIT_OK;
}

int fig_criterion_prepare(fig_Data *d)
{
    char err[512];
    if (jc_paper_solve(d->model, &d->paper, err, sizeof err) != JC_OK ||
        jc_rolling_predict(d->model, &d->rolling, err, sizeof err) != JC_OK) {
        cli_error("plot: %s", err);
        return EXIT_FAIL;
    }
    find_printed(d);
    /* The paper's model measures x = r th from th = 0: the ramp end is at L / r. */
    d->theta_max_rad = d->model->setup.ramp_length_m / d->model->body.radius_m;
    int rc = write_curves(d);
    if (rc == EXIT_OK) rc = write_roots(d);
    return rc;
}

/* The single markers: the printed angle (a vertical line) and the exact
 * model's first N = 0 (a diamond), with their key entries in panel_plot. */
static void panel_markers(FILE *gp, const fig_Data *d)
{
    if (isfinite(d->printed_theta_rad)) {
        fprintf(gp, "# The jump angle printed in the paper's Table 1 for this incline (delete to hide)\n"
                    "PRINTED_THETA = %.10g\n"
                    "set arrow 1 from PRINTED_THETA, graph 0 to PRINTED_THETA, graph 1 nohead lc rgb C_GREY dt 4 lw 2 back\n",
                d->printed_theta_rad);
    }
    if (d->rolling.liftoff.found) {
        const jc_RollingState *s = &d->rolling.liftoff.state;
        fprintf(gp, "# First N = 0 of the exact rolling model (jc_rolling_predict): a diagnostic, the body slips first\n"
                    "EXACT_THETA = %.10g\nEXACT_Y = %.10g\n"
                    "set label 1 '' at EXACT_THETA, EXACT_Y point pt 13 ps 1.8*PS lc rgb C_GREEN front\n",
                s->theta_rad, s->omega_radps * s->omega_radps / d->model->setup.gravity_mps2);
    }
}

/* Key entries are kept short: two columns of them must fit below the graph. */
static void panel_plot(FILE *gp, const fig_Data *d)
{
    fputs("plot CRIT using 1:3 with lines lc rgb C_BLUE lw LW title \"paper: θ'^2/g (Eqs. 1, 5, 6)\", \\\n"
          "     CRIT using 1:($4 > 0 ? $4 : NaN) with lines lc rgb C_RED lw LW title \"paper: cos α/(d cos θ) (Eq. 9)\", \\\n"
          "     CRIT using 1:5 with lines lc rgb C_BLUE lw LW dt (8,5) title \"exact rolling: θ'^2/g\", \\\n"
          "     CRIT using 1:($6 > 0 ? $6 : NaN) with lines lc rgb C_RED lw LW dt (8,5) \\\n"
          "          title \"exact N = 0: (cos α − d sin θ θ''/g)/(d cos θ)\", \\\n"
          "     ROOTS using 1:3 with points pt 6 ps 1.4*PS lw 2 lc rgb C_INK title \"intersections, paper's model\"",
          gp);
    if (d->paper.first >= 0)
        fprintf(gp, ", \\\n     ROOTS using 1:($4 == 1 ? $3 : NaN) with points pt 6 ps 3*PS lw 3 lc rgb C_INK \\\n"
                    "          title \"paper's jump: θ = %.2f rad (%.1f cm)\"",
                d->paper.theta_rad[d->paper.first], d->paper.x_m[d->paper.first] * 100);
    if (isfinite(d->printed_theta_rad))
        fprintf(gp, ", \\\n     keyentry with lines lc rgb C_GREY dt 4 lw 2 title \"printed (Table 1): θ = %.2f rad\"",
                d->printed_theta_rad);
    if (d->rolling.liftoff.found)
        fprintf(gp, ", \\\n     keyentry with points pt 13 ps 1.8*PS lc rgb C_GREEN title \"exact N = 0: θ = %.2f rad (%.1f cm)\"",
                d->rolling.liftoff.state.theta_rad, d->rolling.liftoff.state.x_m * 100);
    fputc('\n', gp);
}

/* Whether the first crossing is narrow: its window (to the next crossing)
 * a small part of the axis, or low in the graph; the inset shows it. Its
 * view in *lo..*hi (rad) and *ylo..*yhi (1/m). */
static int narrow_crossing(const fig_Data *d, double *lo, double *hi, double *ylo, double *yhi)
{
    const jc_PaperResult *p = &d->paper;
    if (p->first < 0) return 0;
    const double a = p->theta_rad[p->first];
    const double b = p->first + 1 < p->root_count ? p->theta_rad[p->first + 1] : a;
    const double w = fmax(b - a, INSET_MIN_WIDTH_RAD);
    const double y = jc_paper_lhs(d->model, a);
    if (!(w < INSET_NARROW_FRACTION * d->theta_max_rad || y < INSET_LOW_FRACTION * d->crit_ymax)) return 0;
    *lo = fmax(a - 0.6 * w, 0.0);
    *hi = fmin(b + 0.6 * w, d->theta_max_rad);
    double y0 = INFINITY, y1 = -INFINITY;
    for (int i = 0; i <= 200; ++i) {
        const double th = *lo + (*hi - *lo) * i / 200.0;
        double el, er;
        exact_sides(d, th, &el, &er);
        const double v[2] = {jc_paper_lhs(d->model, th), el};
        for (int k = 0; k < 2; ++k)
            if (isfinite(v[k])) {
                y0 = fmin(y0, v[k]);
                y1 = fmax(y1, v[k]);
            }
    }
    if (!(y1 > y0)) return 0;
    *ylo = y0 - 0.2 * (y1 - y0);
    *yhi = y1 + 0.2 * (y1 - y0);
    return 1;
}

void fig_criterion_inset(FILE *gp, const fig_Data *d)
{
    double lo, hi, ylo, yhi;
    if (!narrow_crossing(d, &lo, &hi, &ylo, &yhi)) return;
    fig_panel_begin(gp, "paper-criterion inset (the first crossings enlarged)");
    fputs("CRIT = '$criterion'\nROOTS = '$roots'\n"
          "# Where the inset goes, in fractions of the criterion panel's plot area (CR_*: its screen box)\n"
          "IN_X0 = 0.11; IN_X1 = 0.37; IN_Y0 = 0.52; IN_Y1 = 0.88\n"
          "sx(f) = CR_X0 + f * (CR_X1 - CR_X0); sy(f) = CR_Y0 + f * (CR_Y1 - CR_Y0)\n"
          "set lmargin at screen sx(IN_X0); set rmargin at screen sx(IN_X1)\n"
          "set bmargin at screen sy(IN_Y0); set tmargin at screen sy(IN_Y1)\n"
          "# An opaque background: the main panel's curves do not show through\n"
          "set object 1 rect from screen sx(0.015), sy(0.36) to screen sx(0.39), sy(0.985) behind fc rgb 'white' \\\n"
          "    fs solid 1.0 border lc rgb C_GREY lw 1\n"
          "set border 15 lw 1.2 lc rgb C_INK\nset tics font F_SMALL\nset xtics 0.5 out nomirror\nset ytics out nomirror\n"
          "set title 'enlarged: the first crossings (θ in rad)' font F_SMALL offset 0,-0.6\nunset key\n",
          gp);
    fprintf(gp, "set xrange [%.10g:%.10g]\nset yrange [%.10g:%.10g]\nset xtics %g\nset ytics %g\n", lo, hi, ylo, yhi,
            nice_step((hi - lo) / 3), nice_step((yhi - ylo) / 3));
    if (isfinite(d->printed_theta_rad) && d->printed_theta_rad > lo && d->printed_theta_rad < hi)
        fputs("set arrow 1 from PRINTED_THETA, graph 0 to PRINTED_THETA, graph 1 nohead lc rgb C_GREY dt 4 lw 2 back\n", gp);
    if (d->rolling.liftoff.found)
        fputs("set label 1 '' at EXACT_THETA, EXACT_Y point pt 13 ps 1.8*PS lc rgb C_GREEN front\n", gp);
    fputs("plot CRIT using 1:3 with lines lc rgb C_BLUE lw LW, \\\n"
          "     CRIT using 1:($4 > 0 ? $4 : NaN) with lines lc rgb C_RED lw LW, \\\n"
          "     CRIT using 1:5 with lines lc rgb C_BLUE lw LW dt (8,5), \\\n"
          "     CRIT using 1:($6 > 0 ? $6 : NaN) with lines lc rgb C_RED lw LW dt (8,5), \\\n"
          "     ROOTS using 1:3 with points pt 6 ps 1.4*PS lw 2 lc rgb C_INK, \\\n"
          "     ROOTS using 1:($4 == 1 ? $3 : NaN) with points pt 6 ps 3*PS lw 3 lc rgb C_INK\n",
          gp);
}

void fig_criterion_figure(FILE *gp, const fig_Data *d)
{
    fputs("\nset multiplot   # the panel, then an inset on its first crossings when they are narrow\n", gp);
    fig_criterion_panel(gp, d);
    fig_criterion_inset(gp, d);
    fputs("\nunset multiplot\n", gp);
}

void fig_criterion_panel(FILE *gp, const fig_Data *d)
{
    const jc_Model *m = d->model;
    fig_panel_begin(gp, "paper-criterion (the paper's Eq. 9 and the exact N = 0 condition)");
    fputs("CRIT = '$criterion'\nROOTS = '$roots'   # data blocks at the top of this script\n", gp);
    fprintf(gp, "R_CM = %.10g   # rim radius (cm): the top axis shows the distance rolled, r θ\n", m->body.radius_m * 100);
    fputs("set title \"Paper's Eq. 9 vs exact N = 0", gp);
    if (d->caption[0])
        fprintf(gp, " — %.4g° incline, d = %.3g cm, g = %.4g m/s^2", cli_deg(m->setup.incline_rad), m->paper_d_m * 100,
                m->setup.gravity_mps2);
    if (d->crit_clipped)
        fputs("\\n{/*0.8 axis sized to θ'^2/g where the threshold is positive; its peaks where it is not run off the top}",
              gp);
    fputs("\"\n", gp);
    fprintf(gp, "set xlabel 'rotation angle θ (rad)'\n"
                "set ylabel \"θ'^2/g and lift-off threshold (m^{-1})\"\n"
                "set x2label 'distance rolled r θ (cm)'\n"
                "set border 7 lw 1.2 lc rgb C_INK\n"
                "set link x2 via x*R_CM inverse x/R_CM\n"
                "set x2tics out nomirror\n"
                "set xrange [0:%.10g]\nset yrange [0:%.10g]\n"
                "# For a logarithmic axis instead: set logscale y; set yrange [1:*]\n"
                "set key width -10   # gnuplot overestimates text widths: two columns of the key fit\n",
            d->theta_max_rad, d->crit_ymax);
    panel_markers(gp, d);
    panel_plot(gp, d);
    fputs("# The plot area on the page (fractions), for the inset\n"
          "K = 1.0 * GPVAL_TERM_SCALE   # GPVAL_TERM_XMIN etc. are in terminal units over the scale\n"
          "CR_X0 = K * GPVAL_TERM_XMIN / GPVAL_TERM_XSIZE; CR_X1 = K * GPVAL_TERM_XMAX / GPVAL_TERM_XSIZE\n"
          "CR_Y0 = K * GPVAL_TERM_YMIN / GPVAL_TERM_YSIZE; CR_Y1 = K * GPVAL_TERM_YMAX / GPVAL_TERM_YSIZE\n",
          gp);
}
