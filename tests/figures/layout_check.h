/* The layout check of a film frame (cli/films/draw.c reports what it drew
 * where in a draw_Layout): no text box overlaps another text, the body, an
 * arrow, the inset or the legend it is not part of; the body and the arrows
 * keep off the legend and the inset; nothing leaves the frame, and nothing
 * drawn in the inset leaves the inset; the body is drawn at least a stated
 * size across. Geometry only, computed here from the boxes. */
#ifndef JC_LAYOUT_CHECK_H
#define JC_LAYOUT_CHECK_H

#include "films.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* Shapes that only touch, or overlap by less than this (antialiasing), pass. */
#define LC_EPS_PX 0.5

typedef struct {
    int problems;        /* how many were found */
    char first[400];     /* the first, in words */
    double body_px;      /* the largest body drawn, across (px) */
} lc_Result;

static const char *lc_kind_name(draw_BoxKind k)
{
    static const char *const names[] = {"text", "legend", "inset", "body", "arrow"};
    return names[k];
}

static void lc_describe(char *out, size_t len, const draw_Box *b)
{
    if (b->kind == DRAW_BOX_TEXT)
        snprintf(out, len, "text '%s' [%.1f, %.1f]x[%.1f, %.1f]", b->text, b->x0, b->x1, b->y0, b->y1);
    else if (b->kind == DRAW_BOX_ARROW)
        snprintf(out, len, "arrow (%.1f, %.1f)->(%.1f, %.1f)", b->x0, b->y0, b->x1, b->y1);
    else snprintf(out, len, "%s [%.1f, %.1f]x[%.1f, %.1f]", lc_kind_name(b->kind), b->x0, b->x1, b->y0, b->y1);
}

static void lc_problem(lc_Result *r, const char *what, const draw_Box *a, const draw_Box *b)
{
    if (r->problems++ > 0) return;
    char da[160], db[160] = "";
    lc_describe(da, sizeof da, a);
    if (b) lc_describe(db, sizeof db, b);
    snprintf(r->first, sizeof r->first, "%s: %s%s%s", what, da, b ? " and " : "", db);
}

/* Distance from a point to a rectangle (0 inside). */
static double lc_point_rect(double px, double py, const draw_Box *r)
{
    const double dx = fmax(fmax(r->x0 - px, px - r->x1), 0.0), dy = fmax(fmax(r->y0 - py, py - r->y1), 0.0);
    return hypot(dx, dy);
}

static double lc_point_segment(double px, double py, double x0, double y0, double x1, double y1)
{
    const double dx = x1 - x0, dy = y1 - y0, l2 = dx * dx + dy * dy;
    const double t = l2 > 0 ? fmin(fmax(((px - x0) * dx + (py - y0) * dy) / l2, 0.0), 1.0) : 0.0;
    return hypot(px - (x0 + t * dx), py - (y0 + t * dy));
}

/* Whether segments (a, b) and (c, d) cross (proper or touching). */
static int lc_segments_cross(const double a[2], const double b[2], const double c[2], const double d[2])
{
    const double d1 = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    const double d2 = (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]);
    const double d3 = (d[0] - c[0]) * (a[1] - c[1]) - (d[1] - c[1]) * (a[0] - c[0]);
    const double d4 = (d[0] - c[0]) * (b[1] - c[1]) - (d[1] - c[1]) * (b[0] - c[0]);
    return d1 * d2 <= 0 && d3 * d4 <= 0;
}

/* Distance from an arrow's centre line to a rectangle (0 when it crosses it). */
static double lc_segment_rect(const draw_Box *s, const draw_Box *r)
{
    const double a[2] = {s->x0, s->y0}, b[2] = {s->x1, s->y1};
    if (lc_point_rect(a[0], a[1], r) == 0 || lc_point_rect(b[0], b[1], r) == 0) return 0;
    const double c[4][2] = {{r->x0, r->y0}, {r->x1, r->y0}, {r->x1, r->y1}, {r->x0, r->y1}};
    double d = fmin(lc_point_rect(a[0], a[1], r), lc_point_rect(b[0], b[1], r));
    for (int i = 0; i < 4; ++i) {
        if (lc_segments_cross(a, b, c[i], c[(i + 1) % 4])) return 0;
        d = fmin(d, lc_point_segment(c[i][0], c[i][1], a[0], a[1], b[0], b[1]));
    }
    return d;
}

static int lc_is_rect(const draw_Box *b)
{
    return b->kind == DRAW_BOX_TEXT || b->kind == DRAW_BOX_LEGEND || b->kind == DRAW_BOX_INSET;
}

/* Whether a shape (any kind) overlaps a rectangle r by more than LC_EPS_PX. */
static int lc_overlaps_rect(const draw_Box *a, const draw_Box *r)
{
    if (lc_is_rect(a))
        return a->x0 < r->x1 - LC_EPS_PX && r->x0 < a->x1 - LC_EPS_PX && a->y0 < r->y1 - LC_EPS_PX &&
               r->y0 < a->y1 - LC_EPS_PX;
    if (a->kind == DRAW_BOX_BODY) {
        const double rad = 0.5 * (a->x1 - a->x0);
        return lc_point_rect(0.5 * (a->x0 + a->x1), 0.5 * (a->y0 + a->y1), r) < rad - LC_EPS_PX;
    }
    return lc_segment_rect(a, r) < 0.5 * a->width_px - LC_EPS_PX;
}

/* Whether a shape lies inside the rectangle [x0, x1] x [y0, y1]. */
static int lc_inside(const draw_Box *a, double x0, double y0, double x1, double y1)
{
    const double pad = a->kind == DRAW_BOX_ARROW ? 0.5 * a->width_px : 0.0;
    const double ax0 = fmin(a->x0, a->x1) - pad, ax1 = fmax(a->x0, a->x1) + pad;
    const double ay0 = fmin(a->y0, a->y1) - pad, ay1 = fmax(a->y0, a->y1) + pad;
    return ax0 >= x0 - LC_EPS_PX && ax1 <= x1 + LC_EPS_PX && ay0 >= y0 - LC_EPS_PX && ay1 <= y1 + LC_EPS_PX;
}

/* Whether the pair (a, r), r a rectangle, may not overlap. */
static int lc_must_not_overlap(const draw_Box *a, const draw_Box *r)
{
    const int a_text = a->kind == DRAW_BOX_TEXT, a_shape = a->kind == DRAW_BOX_BODY || a->kind == DRAW_BOX_ARROW;
    switch (r->kind) {
    case DRAW_BOX_TEXT: /* text against text anywhere, and the body and arrows of its own panel */
        return a_text || (a_shape && a->panel == r->panel);
    case DRAW_BOX_LEGEND: /* nothing but its own texts */
        return a->panel != DRAW_PANEL_LEGEND && (a_text || a_shape || a->kind == DRAW_BOX_INSET);
    case DRAW_BOX_INSET: /* nothing of the frame's own under it */
        return a->panel == DRAW_PANEL_FRAME && (a_text || a_shape);
    default:
        return 0;
    }
}

/* Checks one frame of width x height pixels: lc_Result counts the problems
 * and keeps the first in words; a body drawn less than min_body_px across
 * (the largest of the frame's drawings of it) is one. */
static lc_Result lc_check(const draw_Layout *L, int width, int height, double min_body_px)
{
    lc_Result r = {0, "", 0.0};
    if (L->dropped > 0) {
        r.problems = 1;
        snprintf(r.first, sizeof r.first, "%d boxes were not recorded (more than %d)", L->dropped, DRAW_LAYOUT_MAX);
    }
    const draw_Box *inset = NULL;
    for (int i = 0; i < L->count; ++i)
        if (L->boxes[i].kind == DRAW_BOX_INSET) inset = &L->boxes[i];
    for (int i = 0; i < L->count; ++i) {
        const draw_Box *a = &L->boxes[i];
        if (a->kind == DRAW_BOX_BODY) r.body_px = fmax(r.body_px, a->x1 - a->x0);
        if (!lc_inside(a, 0, 0, width, height)) lc_problem(&r, "cut by the frame's edge", a, NULL);
        if (a->panel == DRAW_PANEL_INSET && (!inset || !lc_inside(a, inset->x0, inset->y0, inset->x1, inset->y1)))
            lc_problem(&r, "cut by the inset's edge", a, NULL);
        for (int j = 0; j < L->count; ++j) {
            const draw_Box *b = &L->boxes[j];
            if (j == i || !lc_is_rect(b) || (lc_is_rect(a) && j < i)) continue; /* each rectangle pair once */
            if ((lc_must_not_overlap(a, b) || (lc_is_rect(a) && lc_must_not_overlap(b, a))) && lc_overlaps_rect(a, b))
                lc_problem(&r, "overlap", a, b);
        }
    }
    if (r.body_px < min_body_px) {
        char msg[200];
        snprintf(msg, sizeof msg, "the body is %.1f px across, less than %.1f", r.body_px, min_body_px);
        if (r.problems++ == 0) snprintf(r.first, sizeof r.first, "%s", msg);
    }
    return r;
}

#endif
