/* Drawing one frame of the animation with cairo: the incline with a distance
 * scale and marks (the paper's jump point, the model's first lift-off, the
 * measured band), the cylinder to scale with every body part where it is,
 * the centre of mass, the contact forces to a stated scale (a scale bar),
 * the centre's whole path and a fading recent trace, readouts, and with a
 * fixed camera a zoom box that follows the body.
 *
 * Geometry. Incline coordinates: x downhill along the incline, y along the
 * outward normal. Picture coordinates (X right, Y up) put the incline
 * descending to the right at angle a:
 *     X = x cos a + y sin a,   Y = -x sin a + y cos a.
 * Pixels: px = W/2 + s (X - Xc), py = H/2 - s (Y - Yc) (cairo's y points down),
 * s in px/m, (Xc, Yc) the picture point at the frame's centre. A part at
 * body angle phi and offset a_p sits at C + a_p (sin psi, cos psi) with
 * psi = theta - cm_angle + phi; the CM at C + d (sin theta, cos theta). */
#ifndef JUMPCYL_DRAW_H
#define JUMPCYL_DRAW_H

#include <jumpcyl/jumpcyl.h>

#include <cairo.h>

typedef struct {
    int width_px, height_px;
    double scale_px_per_m;
    double center_X_m, center_Y_m; /* picture point at the frame's centre */
    double incline_rad;
    double unit_px; /* line widths and text: pixels per unit, from the whole frame's size */
} draw_View;

/* Picture coordinates of the incline point (x, y). */
void draw_picture(double incline_rad, double x, double y, double *X, double *Y);
/* Pixel of the incline point (x, y). */
void draw_to_pixel(const draw_View *v, double x, double y, double *px, double *py);
/* Incline coordinates of a body part's axis (or of the CM with offset d,
 * body angle cm_angle) for the state s. */
void draw_body_point(const jc_Model *m, const jc_State *s, double offset_m, double body_angle_rad, double *x,
                     double *y);

/* A camera that follows the centre along the incline (not across it, so a
 * hop shows as the cylinder leaving the incline), showing about eight rim
 * radii across the frame's shorter side. */
draw_View draw_view_follow(const jc_Model *m, int width_px, int height_px, const jc_State *s);
/* The same with radii rim radii across the shorter side and the line and
 * text unit of the frame the view is part of (the zoom box). */
draw_View draw_view_zoom(const jc_Model *m, int width_px, int height_px, const jc_State *s, double radii,
                         double unit_px);

/* A fixed laboratory camera: the incline from x_lo_m to x_hi_m and the air
 * above it up to y_top_m (incline coordinates) fill the frame, less margins
 * for the scale's labels under the incline and room for the readouts. */
draw_View draw_view_fixed(const jc_Model *m, int width_px, int height_px, double x_lo_m, double x_hi_m,
                          double y_top_m);

/* The zoom box of a fixed camera's frame: its top-left pixel and size. */
void draw_inset_rect(const draw_View *v, double *x_px, double *y_px, double *w_px, double *h_px);

/* Forces are drawn at px_per_N (from M g and the frame's size, the same in
 * the zoom box); the scale bar, bar_N long (1, 2 or 5 times a power of ten
 * newtons, at most M g), starts at pixel (bar_x_px, bar_y_px) and runs to
 * the right. */
typedef struct {
    double px_per_N, bar_N, bar_x_px, bar_y_px;
} draw_ForceScale;
draw_ForceScale draw_force_scale(const draw_View *v, const jc_Model *m);

typedef struct {
    double x_m, y_m, t_s;
} draw_TracePoint;

/* Places along the incline (x of the contact point, m); NaN: not shown. */
typedef struct {
    double paper_x_m;        /* the paper's printed jump position (Table 1) */
    double model_x_m;        /* the run's first lift-off */
    double measured_x_m;     /* Table 1's measured position ... */
    double measured_error_m; /* ... and its stated error: a band */
} draw_Marks;

typedef struct {
    const jc_Model *model;
    draw_View view;
    const jc_Sample *sample;        /* the state to draw */
    const draw_TracePoint *trace;   /* earlier centres, oldest first; may be NULL */
    int trace_count;
    double trace_fade_s;            /* simulated time over which the trace fades out */
    double slowmo;                  /* playback slow-down, for the clock's caption (0: none) */
    const draw_TracePoint *path;    /* the centre's whole path so far, oldest first; may be NULL */
    int path_count;
    const draw_Marks *marks;        /* may be NULL */
    int zoom_box;                   /* 1: a box in the corner shows the body up close (when it is small) */
} draw_Frame;

/* Draws the whole frame (it paints the background first). */
void draw_frame(cairo_t *cr, const draw_Frame *f);

/* The fill colour of a kind of part, 0..1 each (tests look for it). */
void draw_part_rgb(jc_PartKind kind, double rgb[3]);

/* Colours of what tests look for, 0..1 each. */
typedef enum { DRAW_MARK_PAPER, DRAW_MARK_MODEL, DRAW_MARK_MEASURED, DRAW_NORMAL, DRAW_FRICTION, DRAW_INK } draw_Colour;
void draw_colour_rgb(draw_Colour c, double rgb[3]);

#endif
