/* The trajectory figure's page laid out: the main panel, the whole ramp and
 * the close-up placed in pixels rather than by gnuplot, each plot area sized
 * to its data (trajectory_view.c), the titles wrapped to their room, and the
 * main panel's view grown until the outlines' labels (trajectory_labels.c)
 * fit in it. */
#include "figures.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* The key's rows under the main panel: a row's height, an entry's width (px). */
#define KEY_ROW_PX 32.0
#define KEY_ENTRY_PX 330.0
/* F_TITLE's mean character width (px) on the PNG page. */
#define TITLE_CHAR_PX 14.5
/* The close-up is drawn only when the gap is thinner than this in the main
 * panel (and the close-up spans less than half of the main panel's view). */
#define CLOSEUP_GAP_PX 40.0
/* Rounds of growing the main panel's view until its labels fit. */
#define LAYOUT_ROUNDS 6

/* ---- the layout ---- */

/* The parts of a title, joined with ", " into lines no wider than
 * width_px (estimated); "\n" between lines, as gnuplot reads it. */
static int wrap_title(const char *const *parts, int n, double width_px, char *out, size_t len)
{
    const size_t max_chars = (size_t)fmax(width_px / TITLE_CHAR_PX, 20);
    size_t line = 0;
    int lines = 1;
    out[0] = '\0';
    for (int i = 0; i < n; ++i) {
        size_t chars = 0;
        for (const char *s = parts[i]; *s; ++s) chars += ((unsigned char)*s & 0xC0) != 0x80;
        const size_t used = strlen(out);
        if (i > 0 && line + 2 + chars > max_chars) {
            snprintf(out + used, len - used, ",\\n%s", parts[i]);
            line = chars;
            ++lines;
        } else {
            snprintf(out + used, len - used, "%s%s", i ? ", " : "", parts[i]);
            line += (i ? 2 : 0) + chars;
        }
    }
    return lines;
}

/* The width a title centred over a frame's plot area may take in its region. */
static double title_room(const fig_Frame *f)
{
    const double c = 0.5 * (f->area.lo_X + f->area.hi_X);
    return 2 * fmin(c - f->region.lo_X, f->region.hi_X - c) - 30;
}

/* The three titles, wrapped to their regions' widths. */
static void make_titles(const fig_Data *d, const jc_Sample *apex, fig_Layout *l, fig_Titles *t, double sep_cm)
{
    char a[160], b[120], c[120], e[80];
    if (d->zoomed)
        snprintf(a, sizeof a, "Path to scale: x = %.3g–%.3g cm down the incline (t = %.3g–%.3g s)", d->zoom_x_lo_cm,
                 d->zoom_x_hi_cm, d->zoom_t_lo_s, d->zoom_t_hi_s);
    else snprintf(a, sizeof a, "Path to scale: the whole run");
    snprintf(b, sizeof b, "%s", d->zoomed ? "around the first lift-off and the hops" : "nothing lifts off");
    snprintf(c, sizeof c, "outlines at the events, at least %.3g cm apart", sep_cm);
    const char *pm[] = {a, b, c};
    l->title_lines[0] = wrap_title(pm, 3, title_room(&l->main), t->main, sizeof t->main);
    snprintf(a, sizeof a, "The whole ramp (%.4g cm)", d->model->setup.ramp_length_m * 100);
    const char *pr[] = {a, "in red: the main panel's view"};
    l->title_lines[1] = wrap_title(pr, 2, title_room(&l->ramp), t->ramp, sizeof t->ramp);
    l->title_lines[2] = 0;
    if (apex) {
        snprintf(a, sizeof a, "Close-up: the first flight at its highest");
        snprintf(e, sizeof e, "t = %.4g s, gap %.3g mm", apex->state.t_s, apex->gap_m * 1e3);
        const char *pc[] = {a, e};
        l->title_lines[2] = wrap_title(pc, 2, title_room(&l->closeup), t->closeup, sizeof t->closeup);
    }
}

/* The legend's entries: the centre, each off-centre part, G, the outlines. */
static int key_entries(const jc_Model *m)
{
    int n = 2 + !fig_cm_on_a_part(m);
    for (int i = 0; i < m->setup.body.part_count; ++i) n += fig_off_centre(&m->setup.body.parts[i]);
    return n;
}

/* The main panel's frame for its box, with room below for the key: as
 * many rows as the plot area's width needs (gnuplot fills a row across
 * it). */
static void main_frame(fig_Layout *l, fig_Box box, int entries, int alone, int *on_top)
{
    const double top = fig_title_px(l->title_lines[0]);
    l->key_rows = 1;
    for (int k = 0; k < 3; ++k) {
        const double bottom = FIG_MARGIN_B_PX + l->key_rows * KEY_ROW_PX + 8;
        l->main = fig_frame_in(fig_main_region(box, top, bottom, alone, on_top), box, top, bottom, 0);
        const int cols = (int)fmax(1, floor(fig_box_w(l->main.area) / KEY_ENTRY_PX));
        const int rows = (entries + cols - 1) / cols;
        if (rows == l->key_rows) break;
        l->key_rows = rows;
    }
}

/* The layout: the main panel's box grown until its labels fit in it. */
void fig_trajectory_lay_out(const fig_Data *d, const fig_Path *path, double t_lo, double t_hi, const fig_Outline *o, int n,
                    fig_Box *labels, fig_Layout *l, fig_Titles *t, const jc_Sample *apex, double sep_cm)
{
    const jc_Model *m = d->model;
    fig_Box box = fig_curves_box(d, path, t_lo, t_hi), ramp = fig_curves_box(d, path, 0, d->t_max_s);
    for (int i = 0; i < n; ++i) fig_box_add(&box, o[i].c, m->body.radius_m * 100);
    box = fig_box_margin(box);
    fig_box_add(&ramp, fig_picture(m->setup.incline_rad, 0, 0), 0);
    fig_box_add(&ramp, fig_picture(m->setup.incline_rad, m->setup.ramp_length_m, 0), 0);
    ramp = fig_box_margin(ramp);
    const fig_Box close = apex ? fig_closeup_box(d, apex) : fig_empty_box;
    memset(l, 0, sizeof *l);
    l->title_lines[0] = 2;
    l->title_lines[1] = l->title_lines[2] = 1;
    for (int round = 0; round < LAYOUT_ROUNDS; ++round) {
        int on_top;
        /* The whole ramp adds nothing when the main panel shows nearly all of it. */
        const double tol = 0.03 * fmax(fig_box_w(ramp), fig_box_h(ramp));
        l->ramp_shown = !(box.lo_X <= ramp.lo_X + tol && box.hi_X >= ramp.hi_X - tol && box.lo_Y <= ramp.lo_Y + tol &&
                          box.hi_Y >= ramp.hi_Y - tol);
        l->closeup_shown = apex != NULL;
        main_frame(l, box, key_entries(m), !l->ramp_shown && !l->closeup_shown, &on_top);
        l->closeup_shown = apex && 100 * apex->gap_m * fig_px_per_cm(&l->main) < CLOSEUP_GAP_PX;
        if (!l->ramp_shown && !l->closeup_shown) main_frame(l, box, key_entries(m), 1, &on_top);
        fig_side_frames(l, on_top, ramp, close);
        if (l->closeup_shown) {
            const fig_Box v = l->closeup.view;
            l->closeup_shown = fig_box_w(v) < 0.5 * fig_box_w(l->main.view) && fig_box_h(v) < 0.5 * fig_box_h(l->main.view);
            if (!l->ramp_shown && !l->closeup_shown) main_frame(l, box, key_entries(m), 1, &on_top);
            fig_side_frames(l, on_top, ramp, close);
        }
        /* The titles' lines set the frames' room, the frames the titles' widths. */
        for (int k = 0; k < 2; ++k) {
            make_titles(d, l->closeup_shown ? apex : NULL, l, t, sep_cm);
            fig_side_frames(l, on_top, ramp, close);
        }
        make_titles(d, l->closeup_shown ? apex : NULL, l, t, sep_cm);
        const int outside = fig_place_outline_labels(d, path, &l->main, t_lo, t_hi, o, n, labels);
        if (outside == 0 && round > 0) break;
        const double s = fig_px_per_cm(&l->main);
        for (int i = 0; i < n; ++i) {
            const fig_Box b = labels[i];
            const double pad = 8;
            const fig_Pt lo = {l->main.view.lo_X + (b.lo_X - pad - l->main.area.lo_X) / s,
                               l->main.view.lo_Y + (b.lo_Y - pad - l->main.area.lo_Y) / s};
            const fig_Pt hi = {l->main.view.lo_X + (b.hi_X + pad - l->main.area.lo_X) / s,
                               l->main.view.lo_Y + (b.hi_Y + pad - l->main.area.lo_Y) / s};
            fig_box_join(&box, (fig_Box){lo.X, hi.X, lo.Y, hi.Y});
        }
    }
}
