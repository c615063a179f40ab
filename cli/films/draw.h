/* Drawing one frame of the animation with cairo: the incline with a distance
 * scale, the cylinder to scale with every body part where it is, the centre
 * of mass, the contact forces, a fading trace of the centre, a clock.
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

typedef struct {
    double x_m, y_m, t_s;
} draw_TracePoint;

typedef struct {
    const jc_Model *model;
    draw_View view;
    const jc_Sample *sample;        /* the state to draw */
    const draw_TracePoint *trace;   /* earlier centres, oldest first; may be NULL */
    int trace_count;
    double trace_fade_s;            /* simulated time over which the trace fades out */
    double slowmo;                  /* playback slow-down, for the clock's caption (0: none) */
} draw_Frame;

/* Draws the whole frame (it paints the background first). */
void draw_frame(cairo_t *cr, const draw_Frame *f);

/* The fill colour of a kind of part, 0..1 each (tests look for it). */
void draw_part_rgb(jc_PartKind kind, double rgb[3]);

#endif
