/* jumpcyl map: a regime map of the first lift-off over two setup options.
 * The cells where the body lifts off are coloured by where it lifts off
 * (one continuous palette); the cells where it does not lift off on the
 * ramp, slides from the start, or is not a valid setup have colours of
 * their own, outside the palette; failed runs are hatched. The paper's
 * setups are marked where they fall inside the map.
 *
 * The cells are drawn as an image (`with image`) when both axes are evenly
 * spaced, which gives one seamless raster in every format, and as boxes
 * between the midpoints of neighbouring values otherwise (a list such as
 * mu=0.1,0.2,0.5). */
#include "figures.h"

#include <math.h>
#include <string.h>

/* Relative tolerance of "evenly spaced", against rounding in the values. */
#define EVEN_REL 1e-6
/* SVG viewers smooth an embedded image as they scale it up, blurring the
 * cells: up to this many cells, each is a rectangle of its own (about 60
 * bytes each and layer); beyond, the SVG holds the image. */
#define SVG_PIXEL_CELLS 50000L

/* Viridis (perceptually uniform, colour-blind safe, legible in grey): the
 * lift-off position. The categories use colours it does not contain. */
static const char *const palette =
    "set palette defined (0 '#440154', 1 '#472D7B', 2 '#3B528B', 3 '#2C728E', 4 '#21918C', \\\n"
    "                     5 '#28AE80', 6 '#5EC962', 7 '#ADDC30', 8 '#FDE725')\n";

static const char *const cell_names[FIG_CELL_KINDS] = {
    "first lift-off on the ramp", "no lift-off on the ramp", "slides from the start", "not a valid setup",
    "run failed",
};

static int evenly_spaced(const fig_MapAxis *a)
{
    const double step = (a->values[a->count - 1] - a->values[0]) / (double)(a->count - 1);
    for (long k = 1; k < a->count; ++k)
        if (fabs(a->values[k] - a->values[k - 1] - step) > EVEN_REL * fabs(step)) return 0;
    return 1;
}

/* The cell edges of an axis: halfway between neighbouring values, and half a
 * neighbour's spacing beyond the first and last. */
static double edge(const fig_MapAxis *a, long k)
{
    const double *v = a->values;
    const long n = a->count;
    if (k == 0) return v[0] - 0.5 * (v[1] - v[0]);
    if (k == n) return v[n - 1] + 0.5 * (v[n - 1] - v[n - 2]);
    return 0.5 * (v[k - 1] + v[k]);
}

/* NAME_LO(i, v), NAME_HI(i, v): the edges of cell i (value v) of an axis:
 * v -+ half a step when the values are evenly spaced, else an array of the
 * edges (1-based, as gnuplot's arrays are), widened by a hair so that
 * neighbouring boxes overlap: antialiased edges would leave light seams. */
static void write_edges(FILE *gp, const char *name, const fig_MapAxis *a, int even)
{
    fprintf(gp, "%s_PAD = %.10g   # the overlap of neighbouring boxes\n", name,
            1e-3 * (edge(a, a->count) - edge(a, 0)));
    if (even) {
        fprintf(gp, "%s_HALF = %.10g   # half a cell\n%s_LO(i, v) = v - %s_HALF - %s_PAD\n"
                    "%s_HI(i, v) = v + %s_HALF + %s_PAD\n",
                name, 0.5 * (a->values[a->count - 1] - a->values[0]) / (double)(a->count - 1), name, name, name, name,
                name, name);
        return;
    }
    fprintf(gp, "# The cells' edges, halfway between neighbouring values.\narray %s_EDGES[%ld] = [", name,
            a->count + 1);
    for (long k = 0; k <= a->count; ++k)
        fprintf(gp, "%s%.10g", k == 0 ? "" : k % 8 == 0 ? ", \\\n    " : ", ", edge(a, k));
    fprintf(gp, "]\n%s_LO(i, v) = %s_EDGES[i + 1] - %s_PAD\n%s_HI(i, v) = %s_EDGES[i + 2] + %s_PAD\n", name, name,
            name, name, name, name);
}

static void write_cells(FILE *gp, const fig_Map *m, long counts[FIG_CELL_KINDS], double *lo_cm, double *hi_cm)
{
    fig_block_begin(gp, "map");
    fputs("# jumpcyl map: one row per case of the map, case = iy * (number of x values) + ix, in case order\n"
          "# (the rows of STEM.csv); x varies fastest, a blank line ends each row of x.\n"
          "# lift_cm: the first lift-off's distance down the ramp (cm), NaN when there is none.\n"
          "# kind: 0 first lift-off on the ramp, 1 no lift-off on the ramp, 2 slides from the start,\n"
          "#       3 not a valid setup, 4 run failed. ix, iy: the cell's indices from 0.\n",
          gp);
    fprintf(gp, "# columns: x y lift_cm kind ix iy   (x: %s; y: %s)\n", m->x.label, m->y.label);
    memset(counts, 0, FIG_CELL_KINDS * sizeof *counts);
    *lo_cm = INFINITY;
    *hi_cm = -INFINITY;
    for (long iy = 0; iy < m->y.count; ++iy) {
        for (long ix = 0; ix < m->x.count; ++ix) {
            const long i = iy * m->x.count + ix;
            const int kind = m->kind[i] < FIG_CELL_KINDS ? m->kind[i] : FIG_CELL_FAILED;
            const double lift = kind == FIG_CELL_LIFTOFF ? m->liftoff_cm[i] : NAN;
            ++counts[kind];
            if (isfinite(lift)) {
                *lo_cm = fmin(*lo_cm, lift);
                *hi_cm = fmax(*hi_cm, lift);
                fprintf(gp, "%.10g %.10g %.10g %d %ld %ld\n", m->x.values[ix], m->y.values[iy], lift, kind, ix, iy);
            } else {
                fprintf(gp, "%.10g %.10g NaN %d %ld %ld\n", m->x.values[ix], m->y.values[iy], kind, ix, iy);
            }
        }
        fputc('\n', gp);
    }
    fig_block_end(gp);
}

/* The paper's setups: their points (a data block) ... */
static void write_paper_points(FILE *gp, const fig_Map *m)
{
    if (m->paper_count == 0) return;
    fig_block_begin(gp, "paper");
    fputs("# The paper's setups (its preset at 15, 30 and 45 deg) inside the map. columns: x y\n", gp);
    for (int k = 0; k < m->paper_count; ++k) fprintf(gp, "%.10g %.10g\n", m->paper_x[k], m->paper_y[k]);
    fig_block_end(gp);
}

/* ... and their labels, placed inside the frame. */
static void write_paper_labels(FILE *gp, const fig_Map *m, double x0, double x1, double y0, double y1)
{
    for (int k = 0; k < m->paper_count; ++k) {
        const double fx = (m->paper_x[k] - x0) / (x1 - x0), fy = (m->paper_y[k] - y0) / (y1 - y0);
        const char *align = fx < 0.15 ? "left" : fx > 0.85 ? "right" : "center";
        const double dx = fx < 0.15 ? 1.0 : fx > 0.85 ? -1.0 : 0.0, dy = fy > 0.85 ? -1.6 : 1.6;
        fprintf(gp, "set label %d ", k + 1);
        fig_quote(gp, m->paper_label[k]);
        fprintf(gp, " at %.10g, %.10g %s offset char %g, char %g boxed front font F_SMALL textcolor rgb C_INK\n",
                m->paper_x[k], m->paper_y[k], align, dx, dy);
    }
}

void fig_map_write(FILE *gp, const fig_Map *m)
{
    const int even = evenly_spaced(&m->x) && evenly_spaced(&m->y);
    const double x0 = edge(&m->x, 0), x1 = edge(&m->x, m->x.count);
    const double y0 = edge(&m->y, 0), y1 = edge(&m->y, m->y.count);
    long counts[FIG_CELL_KINDS];
    double lo, hi;
    write_cells(gp, m, counts, &lo, &hi);
    write_paper_points(gp, m);

    fig_panel_begin(gp, "map (first lift-off over two setup options)");
    fputs("MAP = '$map'\n", gp);
    fputs("# Colours of the cells that do not lift off (not in the palette of the lift-off position).\n"
          "C_NONE = '#D9D9D9'      # no lift-off on the ramp\n"
          "C_SLIDES = C_RED        # slides from the start\n"
          "C_INVALID = '#FFFFFF'   # not a valid setup (and, hatched, a failed run)\n"
          "# The same colours as numbers, for the cells' layer (rgbalpha or rgb variable).\n"
          "hex(c) = int('0x' . c[2:7])\n"
          "KIND_RGB(k) = k == 1 ? hex(C_NONE) : k == 2 ? hex(C_SLIDES) : hex(C_INVALID)\n"
          "R(k) = (KIND_RGB(k) >> 16) & 255\nG(k) = (KIND_RGB(k) >> 8) & 255\nB(k) = KIND_RGB(k) & 255\n",
          gp);
    write_edges(gp, "X", &m->x, evenly_spaced(&m->x));
    write_edges(gp, "Y", &m->y, evenly_spaced(&m->y));
    fputs("set title ", gp);
    fig_quote(gp, m->title);
    fputs(" . \"\\n\" . ", gp);
    fig_quote(gp, m->subtitle);
    fputs("\nset xlabel ", gp);
    fig_quote(gp, m->x.label);
    fputs("\nset ylabel ", gp);
    fig_quote(gp, m->y.label);
    fprintf(gp, "\nset xrange [%.10g:%.10g]\nset yrange [%.10g:%.10g]\n", x0, x1, y0, y1);
    /* Nothing lifts off: the scale spans the ramp, where a lift-off would be. */
    if (!(lo <= hi)) {
        lo = 0.0;
        hi = m->ramp_cm;
    } else if (hi - lo < 1e-6 * fmax(1.0, hi)) {
        lo -= 1.0;
        hi += 1.0;
    }
    fprintf(gp, "set cbrange [%.10g:%.10g]\n", lo, hi);
    fputs(palette, gp);
    fputs("set cblabel 'first lift-off x (cm)'\nset colorbox vertical\nset cbtics out nomirror\n"
          "unset grid\nset tics front\nset border 15 front lw 1.2 lc rgb C_INK\n"
          "set style fill solid 1.0 noborder\n",
          gp);
    write_paper_labels(gp, m, x0, x1, y0, y1);

    const char *pixels = m->format == FIG_SVG && m->x.count * m->y.count <= SVG_PIXEL_CELLS ? " pixels" : "";
    if (even)
        fprintf(gp, "plot MAP using 1:2:($4 == 0 ? $3 : NaN) with image%s, \\\n"
                    "     MAP using 1:2:(R($4)):(G($4)):(B($4)):($4 == 0 ? 0 : 255) with rgbalpha%s",
                pixels, pixels);
    else
        fputs("plot MAP using 1:2:(X_LO($5, $1)):(X_HI($5, $1)):(Y_LO($6, $2)):(Y_HI($6, $2)):($4 == 0 ? $3 : NaN) \\\n"
              "         with boxxyerror fc palette, \\\n"
              "     MAP using ($4 == 0 ? NaN : $1):2:(X_LO($5, $1)):(X_HI($5, $1)):(Y_LO($6, $2)):(Y_HI($6, $2)):(KIND_RGB($4)) \\\n"
              "         with boxxyerror fc rgb variable", gp);
    if (counts[FIG_CELL_FAILED] > 0)
        fputs(", \\\n     MAP using ($4 == 4 ? $1 : NaN):2:(X_LO($5, $1)):(X_HI($5, $1)):(Y_LO($6, $2)):(Y_HI($6, $2)) \\\n"
              "         with boxxyerror fs pattern 4 transparent noborder fc rgb C_INK", gp);
    /* The key: only the kinds of cell the map holds, each with its count. */
    static const char *const samples[FIG_CELL_KINDS] = {
        NULL, "fs solid 1.0 border lc rgb C_GREY fc rgb C_NONE", "fs solid 1.0 border lc rgb C_GREY fc rgb C_SLIDES",
        "fs solid 1.0 border lc rgb C_GREY fc rgb C_INVALID", "fs pattern 4 border lc rgb C_INK fc rgb C_INK"};
    for (int k = 1; k < FIG_CELL_KINDS; ++k) {
        if (counts[k] == 0) continue;
        char entry[96];
        snprintf(entry, sizeof entry, "%s (%ld)", cell_names[k], counts[k]);
        fprintf(gp, ", \\\n     NaN with boxes %s title ", samples[k]);
        fig_quote(gp, entry);
    }
    if (m->paper_count > 0) {
        fputs(", \\\n     '$paper' using 1:2 with points pt 7 ps 2.2*PS lc rgb 'white' notitle, \\\n"
              "     '$paper' using 1:2 with points pt 6 ps 2.2*PS lw 2 lc rgb C_INK title ",
              gp);
        fig_quote(gp, m->paper_differs ? "the paper's values of these two options (its other values differ)"
                                       : "the paper's setups");
    }
    fputc('\n', gp);
}
