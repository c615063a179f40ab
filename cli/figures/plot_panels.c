/* The three panels drawn from a run of the full model: contact forces,
 * hops (gap and speed), energy. The numbers come from the data files that
 * plot_run.c wrote; ranges are fixed here so that labels get room. */
#include "figures.h"

#include <math.h>

/* Top part of the forces and path panels kept free for labels. */
#define LABEL_HEADROOM 0.62
/* The forces panel's event labels hang from the top: a line of this many
 * characters takes this fraction of the plot's height per character (the
 * labels' font on a panel 750 px high), plus a margin. Shorter labels
 * leave the curves more of the height, up to FORCES_HEADROOM_MAX (the
 * dense events' ticks take the top 8 %). */
#define EVENT_LABEL_CHAR_HEIGHT 0.0245
#define EVENT_LABEL_MARGIN 0.03
#define FORCES_HEADROOM_MAX 0.9
/* More events than this are marked by ticks at the top instead of lines. */
#define DENSE_EVENTS 60

/* NAME = '$what': the data block of that name at the top of the script. */
static void data_var(FILE *gp, const char *name, const char *what)
{
    fprintf(gp, "%s = '$%s'\n", name, what);
}

/* The panel's name and the setup; on a page of its own, what of a run
 * rocking for ever is shown in a second line (the overview's page title
 * says it there). */
static void title(FILE *gp, const fig_Data *d, const char *what)
{
    char cut[256] = "";
    if (d->caption[0]) fig_cut_caption(d, cut, sizeof cut);
    fprintf(gp, "set title \"%s%s%s%s%s%s\"\n", what, d->caption[0] ? " — " : "", d->caption, cut[0] ? "\\n{/*0.8 " : "",
            cut, cut[0] ? "}" : "");
}

/* Whether the panels show the zoom on the lift-off and hops (overview). */
static int zoomed(const fig_Data *d) { return d->zoom_wanted && d->zoomed; }

/* The horizontal axis: distance down the incline, or time when the body
 * went back and forth (plot_run.c). AX, EX, HX are the columns holding it in
 * the run, events and hops files. */
static void x_axis(FILE *gp, const fig_Data *d)
{
    const char *zoom = zoomed(d) ? ", zoomed (page title)" : "";
    if (d->time_axis)
        fprintf(gp, "# The body went back and forth: against time (for distance: AX = 2; EX = 1; HX = 1)\n"
                    "AX = 1; EX = 2; HX = 2\nset xlabel 'time t (s)%s'\n", zoom);
    else
        fprintf(gp, "# Against distance (for time: AX = 1; EX = 2; HX = 2; and the xlabel and xrange)\n"
                    "AX = 2; EX = 1; HX = 1\nset xlabel 'distance of the centre down the incline x (cm)%s'\n", zoom);
    if (zoomed(d)) fputs("# Zoomed on the first lift-off and the hops; the whole run: set autoscale x\n", gp);
    fprintf(gp, "set xrange [%.10g:%.10g]\n", d->axis_min, d->axis_max);
}

/* Left axis for one quantity, right axis for another, each coloured like its curve. */
static void two_axes(FILE *gp, const char *left, const char *left_colour, const char *right, const char *right_colour)
{
    fprintf(gp, "set ylabel \"%s\" textcolor rgb %s\nset y2label \"%s\" textcolor rgb %s\n"
                "set border 11 lw 1.2 lc rgb C_INK\nset ytics nomirror\nset y2tics out nomirror\n",
            left, left_colour, right, right_colour);
}

/* Event lines across the graph and their labels hanging from the top,
 * left or right of their lines (the events block's column 5), in one or
 * two lines (columns 6 and 7). A label not on a side is the empty string,
 * not a NaN position: gnuplot 5.4 crashes on a rotated label plot whose
 * every point is undefined. */
static void plot_events(FILE *gp)
{
    fputs(", \\\n     EVENTS using (column(EX)):(EV_FROM):(0):(YMAX - EV_FROM) with vectors nohead lc rgb C_GREY dt EV_DT lw 1.5 title 'events'",
          gp);
    static const struct {
        const char *side;
        int column;
        double offset;
    } lines[] = {{"<", 6, -2.3}, {"<", 7, -0.9}, {">", 6, 0.75}, {">", 7, 2.15}};
    for (size_t i = 0; i < sizeof lines / sizeof lines[0]; ++i)
        fprintf(gp, ", \\\n     EVENTS using (column(EX)):(YMAX):($5 %s 0 ? strcol(%d) : '') with labels rotate by 90 right offset %g,-0.4 "
                    "font F_SMALL textcolor rgb C_INK notitle",
                lines[i].side, lines[i].column, lines[i].offset);
}

/* The part of the forces panel's height the curves may take: below the
 * longest event label (LABEL_HEADROOM for the longest labels). */
static double forces_headroom(const fig_Data *d)
{
    const double room = 1.0 - EVENT_LABEL_CHAR_HEIGHT * d->event_label_chars - EVENT_LABEL_MARGIN;
    return fmin(fmax(room, LABEL_HEADROOM), FORCES_HEADROOM_MAX);
}

void fig_forces_panel(FILE *gp, const fig_Data *d)
{
    const jc_Setup *s = &d->model->setup;
    fig_panel_begin(gp, "forces (normal force and friction ratio along the ramp)");
    data_var(gp, "RUN", "run");
    data_var(gp, "EVENTS", "events");
    const double headroom = forces_headroom(d);
    const double ymin = fmin(0.0, d->n_min), ymax = fmax(d->n_max, 0.1) / headroom;
    const double mu = fmax(s->mu_static, s->mu_kinetic);
    /* A huge mu (the rolling limit) would flatten the curve: keep it in view. */
    const double top = d->ratio_max > 0 ? fmax(d->ratio_max, fmin(mu, 3 * d->ratio_max)) : fmax(mu, 0.1);
    fprintf(gp, "MU_S = %.10g   # static friction coefficient\nMU_K = %.10g   # kinetic\n"
                "YMIN = %.10g\nYMAX = %.10g\n",
            s->mu_static, s->mu_kinetic, ymin, ymax + 0.02 * (ymax - ymin));
    /* Hundreds of events would grey the whole graph: then only ticks at the top. */
    if (d->run.event_count > DENSE_EVENTS)
        fputs("EV_FROM = YMAX - 0.08 * (YMAX - YMIN); EV_DT = 1   # events are dense: ticks at the top\n", gp);
    else
        fputs("EV_FROM = YMIN; EV_DT = 2   # dashed event lines across the graph\n", gp);
    title(gp, d, "Contact forces");
    x_axis(gp, d);
    two_axes(gp, "normal force N / (M g cos α)", "C_BLUE", "friction / normal force |F| / N", "C_RED");
    fprintf(gp, "set yrange [YMIN:YMAX]\nset y2range [0:%.10g]\n", top / headroom);
    fputs("# Friction band: rolling without slipping needs |F| <= mu_s N\n"
          "set object 1 rect from graph 0, second 0 to graph 1, second MU_S behind fc rgb C_RED fs transparent solid 0.12 noborder\n",
          gp);
    if (s->mu_kinetic != s->mu_static)
        fputs("set arrow 1 from graph 0, second MU_K to graph 1, second MU_K nohead lc rgb C_RED dt 3 lw 1.5 back\n", gp);
    fputs("plot RUN using (column(AX)):(YMIN):($3 == 2 ? YMAX : YMIN) with filledcurves fc rgb C_GREY fs transparent solid 0.15 \\\n"
          "          title 'in flight', \\\n"
          "     RUN using (column(AX)):4 with lines lc rgb C_BLUE lw LW title 'N / (M g cos α) (left axis)', \\\n"
          "     RUN using (column(AX)):5 axes x1y2 with lines lc rgb C_RED lw LW title '|F| / N (right axis; none in flight)', \\\n"
          "     keyentry with boxes fc rgb C_RED fs transparent solid 0.12 title sprintf('|F| ≤ μ_s N: rolling allowed (μ_s = %g)', MU_S)",
          gp);
    if (s->mu_kinetic != s->mu_static)
        fputs(", \\\n     keyentry with lines lc rgb C_RED dt 3 lw 1.5 title sprintf('μ_k = %g (sliding)', MU_K)", gp);
    plot_events(gp);
    fputc('\n', gp);
}

void fig_path_panel(FILE *gp, const fig_Data *d)
{
    fig_panel_begin(gp, "path (gap under the rim and speed along the ramp)");
    data_var(gp, "RUN", "run");
    data_var(gp, "HOPS", "hops");
    const double gap_top = d->gap_max_mm > 0 ? d->gap_max_mm / LABEL_HEADROOM : 1.0;
    title(gp, d, "Hops");
    x_axis(gp, d);
    two_axes(gp, "gap between rim and incline (mm)", "C_RED", "speed of the centre (m/s)", "C_BLUE");
    /* Both curves stay below LABEL_HEADROOM of the height; the hops' labels
     * are in rows above them (the hops block's label_row). */
    fprintf(gp, "GAP_TOP = %.10g\nset yrange [0:GAP_TOP]\nset y2range [0:%.10g]\n", gap_top,
            d->speed_max_mps > 0 ? d->speed_max_mps / LABEL_HEADROOM : 1.0);
    fprintf(gp, "plot RUN using (column(AX)):6 with filledcurves y=0 fc rgb C_RED fs transparent solid 0.25 notitle, \\\n"
                "     RUN using (column(AX)):6 with lines lc rgb C_RED lw LW title 'gap under the rim (left axis)', \\\n"
                "     RUN using (column(AX)):7 axes x1y2 with lines lc rgb C_BLUE lw LW title 'speed of the centre (right axis)', \\\n"
                "     HOPS using (column(HX)):4 with points pt 9 ps 1.6*PS lc rgb C_INK title 'highest gap of each flight (%d)', \\\n"
                "     HOPS using 7:(GAP_TOP * (0.95 - 0.075 * ($8 < 0 ? 0 : $8))):($8 < 0 ? '' : strcol(6)) with labels font F_SMALL \\\n"
                "          textcolor rgb C_INK notitle\n",
            d->hop_count);
}

void fig_energy_panel(FILE *gp, const fig_Data *d)
{
    fig_panel_begin(gp, "energy (kinetic, potential, losses, and their sum)");
    data_var(gp, "RUN", "run");
    const double span = fmax(d->energy_max_J - d->energy_min_J, 1e-12);
    title(gp, d, "Energy");
    const double t_lo = zoomed(d) ? d->zoom_t_lo_s : 0.0, t_hi = zoomed(d) ? d->zoom_t_hi_s : d->t_max_s;
    fprintf(gp, "set xlabel 'time t (s)%s'\nset ylabel 'energy (J)'\nset xrange [%.10g:%.10g]\nset yrange [%.10g:%.10g]\n"
                "set xzeroaxis lt 1 lw 1 lc rgb C_GREY\n",
            zoomed(d) ? ", zoomed (page title)" : "", t_lo, t_hi > t_lo ? t_hi : t_lo + 1.0,
            d->energy_min_J - 0.05 * span, d->energy_max_J + 0.05 * span);
    fputs("plot RUN using 1:8 with lines lc rgb C_BLUE lw LW title 'kinetic K', \\\n"
          "     RUN using 1:9 with lines lc rgb C_GREEN lw LW title 'potential U (from the start)', \\\n"
          "     RUN using 1:10 with lines lc rgb C_ORANGE lw LW title 'lost to friction', \\\n"
          "     RUN using 1:11 with lines lc rgb C_PURPLE lw LW title 'lost in impacts', \\\n",
          gp);
    if (d->resistance_loss_max_J > 0)
        fputs("     RUN using 1:15 with lines lc rgb C_GREY lw LW title 'lost to air and rolling resistance', \\\n", gp);
    fputs("     RUN using 1:12 with lines lc rgb C_INK lw LW dt (8,5) title 'sum K + U + losses (conserved)'\n", gp);
}
