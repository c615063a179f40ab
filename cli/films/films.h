/* `jumpcyl animate`'s films (cli/films/): one frame drawn with cairo
 * (draw.c), a run's frames (film.c), numbered PNG frames and what becomes
 * of them: ffmpeg's film or a directory of frames (video.c). */
#ifndef JUMPCYL_FILMS_H
#define JUMPCYL_FILMS_H

#include "outputs.h"

#include <jumpcyl/jumpcyl.h>

#include <cairo.h>
#include <stddef.h>
#include <stdio.h>

/* ---- draw.c ---- */

/* Drawing one frame of the animation with cairo: the incline with a distance
 * scale and marks (the paper's jump point, the model's first lift-off, the
 * measured band), the cylinder to scale with every body part where it is,
 * the centre of mass, the contact forces to a stated scale (a scale bar),
 * the centre's whole path and a fading recent trace, readouts, and an
 * inset with the whole ramp when the view follows a body too small to see
 * on it.
 *
 * Geometry. Incline coordinates: x downhill along the incline, y along the
 * outward normal. Picture coordinates (X right, Y up) put the incline
 * descending to the right at angle a:
 *     X = x cos a + y sin a,   Y = -x sin a + y cos a.
 * Pixels: px = W/2 + s (X - Xc), py = H/2 - s (Y - Yc) (cairo's y points down),
 * s in px/m, (Xc, Yc) the picture point at the frame's centre. A part at
 * body angle phi and offset a_p sits at C + a_p (sin psi, cos psi) with
 * psi = theta - cm_angle + phi; the CM at C + d (sin theta, cos theta). */

typedef struct {
    int width_px, height_px;
    double scale_px_per_m;
    double center_X_m, center_Y_m; /* picture point at the frame's centre */
    double incline_rad;
    double unit_px; /* line widths and text: pixels per unit, from the whole frame's size */
} draw_View;

/* Picture coordinates of the incline point (x, y). */
void draw_picture(double incline_rad, double x, double y, double *X, double *Y);
/* Places along the incline (x of the contact point, m); NaN: not shown. */
typedef struct {
    double paper_x_m;        /* the paper's printed jump position (Table 1) */
    double model_x_m;        /* the run's first lift-off */
    double measured_x_m;     /* Table 1's measured position ... */
    double measured_error_m; /* ... and its stated error: a band */
} draw_Marks;

/* Pixel of the incline point (x, y). */
void draw_to_pixel(const draw_View *v, double x, double y, double *px, double *py);
/* Incline coordinates of a body part's axis (or of the CM with offset d,
 * body angle cm_angle) for the state s. */
void draw_body_point(const jc_Model *m, const jc_State *s, double offset_m, double body_angle_rad, double *x,
                     double *y);

/* A camera that follows the centre along the incline (not across it, so a
 * hop shows as the cylinder leaving the incline), showing eight rim radii
 * across the frame's shorter side. */
draw_View draw_view_follow(const jc_Model *m, int width_px, int height_px, const jc_State *s);

/* A fixed laboratory camera: the incline from x_lo_m to x_hi_m and the air
 * above it up to y_top_m (incline coordinates) as large as they fit, with
 * margins for the scale's labels under the incline, clear of the legend in
 * the top right corner (the readouts, and the key of marks: may be NULL). */
draw_View draw_view_fixed(const jc_Model *m, int width_px, int height_px, double x_lo_m, double x_hi_m,
                          double y_top_m, const draw_Marks *marks);

/* The inset beside a view v that follows the body: the incline from
 * x_lo_m to x_hi_m and the air above it up to y_top_m fitted into a box in
 * the bottom left corner, under the incline and its scale's labels.
 * *overview: the view in the box (its size the box's); (*x_px, *y_px): the
 * box's top left pixel. */
void draw_inset(const draw_View *v, double x_lo_m, double x_hi_m, double y_top_m, draw_View *overview,
                double *x_px, double *y_px);

/* The legend's box in a frame of view v (readouts, force scale and the
 * key of marks, which may be NULL): x0, y0, x1, y1 in pixels. */
void draw_legend_box(const draw_View *v, const draw_Marks *marks, double box[4]);

/* Forces are drawn at px_per_N (from M g and the frame's size); the scale bar, bar_N long (1, 2 or 5 times a power of ten
 * newtons, at most M g), starts at pixel (bar_x_px, bar_y_px) and runs to
 * the right. */
typedef struct {
    double px_per_N, bar_N, bar_x_px, bar_y_px;
} draw_ForceScale;
draw_ForceScale draw_force_scale(const draw_View *v, const jc_Model *m);

typedef struct {
    double x_m, y_m, t_s;
} draw_TracePoint;


/* What a frame drew where, for a layout check (tests/figures): every text's
 * ink box, the readouts' block (the legend), the inset, the body's rim and
 * each force arrow, in the frame's pixels. */
typedef enum { DRAW_BOX_TEXT, DRAW_BOX_LEGEND, DRAW_BOX_INSET, DRAW_BOX_BODY, DRAW_BOX_ARROW } draw_BoxKind;

/* Which part of the frame a box belongs to: the frame itself, the inset (its
 * boxes must lie inside the inset's box) or the legend (the readouts). */
typedef enum { DRAW_PANEL_FRAME, DRAW_PANEL_INSET, DRAW_PANEL_LEGEND } draw_Panel;

typedef struct {
    draw_BoxKind kind;
    draw_Panel panel;
    /* Text, legend, inset: the rectangle's corners (x0 < x1, y0 < y1). Body:
     * the rim's bounding square, the rim the circle inscribed in it. Arrow:
     * its tail (x0, y0) and tip (x1, y1), width_px across its head. */
    double x0, y0, x1, y1, width_px;
    char text[48]; /* text: its first characters (for messages) */
} draw_Box;

#define DRAW_LAYOUT_MAX 128
typedef struct {
    int count;    /* boxes[0 .. count) */
    int dropped;  /* boxes that did not fit */
    draw_Panel panel_now;  /* the panel being drawn (draw.c sets it) ... */
    double panel_box[4];   /* ... and its box: x0, y0, x1, y1 */
    draw_Box boxes[DRAW_LAYOUT_MAX];
} draw_Layout;

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
    draw_View overview;             /* the inset's whole-ramp view (draw_inset); width_px 0: none */
    double inset_x_px, inset_y_px;  /* the inset's top left corner */
    draw_Layout *layout;            /* NULL, or filled with what was drawn where */
} draw_Frame;

/* Draws the whole frame (it paints the background first). */
void draw_frame(cairo_t *cr, const draw_Frame *f);

/* The fill colour of a kind of part, 0..1 each (tests look for it). */
void draw_part_rgb(jc_PartKind kind, double rgb[3]);

/* Colours of what tests look for, 0..1 each. */
typedef enum { DRAW_MARK_PAPER, DRAW_MARK_MODEL, DRAW_MARK_MEASURED, DRAW_NORMAL, DRAW_FRICTION, DRAW_INK } draw_Colour;
void draw_colour_rgb(draw_Colour c, double rgb[3]);

/* ---- film.c ---- */

typedef enum { FILM_CAMERA_FIXED, FILM_CAMERA_FOLLOW } film_Camera;

/* A run made into frames: frame film_frame(film, i) shows sample i. */
typedef struct {
    const jc_Model *model;
    const jc_Run *run;
    int width_px, height_px;
    double slowmo;          /* playback slow-down: the trace fades over 2 s of playback */
    film_Camera camera;
    draw_Marks marks;
    double x_lo_m, x_hi_m, y_top_m; /* the fixed camera's stretch of incline and air */
    draw_View fixed;        /* the fixed camera's view of them (the whole ramp, or the way travelled) */
    int fixed_follows;      /* 1: the body is too small on it; a camera follows, the inset shows it */
    draw_TracePoint *trace; /* the run's centres */
} film_Film;

/* 0, or -1 out of memory; marks may be NULL (none). Release with film_free. */
int film_init(film_Film *film, const jc_Model *m, const jc_Run *run, int width_px, int height_px, double slowmo,
              film_Camera camera, const draw_Marks *marks);
void film_free(film_Film *film);
/* The frame that shows the run's sample i (it points into film). */
draw_Frame film_frame(const film_Film *film, int i);

/* ---- video.c ---- */

typedef enum { VID_GIF, VID_MP4, VID_FRAMES } vid_Format;

#define VID_FRAME_NAME "frame-%05d.png"
#define VID_FRAME_PATTERN "frame-%05d.png" /* ffmpeg's image2 pattern: the same text */
#define VID_MAX_FRAMES 100000              /* five digits */

/* .gif, .mp4, or a directory: a name ending in '/' or without extension.
 * -1 for any other extension. */
int vid_format_from_path(const char *path, vid_Format *f);
/* dir/frame-NNNNN.png; -1 if it does not fit. */
int vid_frame_path(char *out, size_t len, const char *dir, int index);

typedef struct {
    char *argv[32];
    char fps[32];
    char input[CLI_PATH_MAX + 8];  /* file:/abs/frame-%05d.png */
    char output[CLI_PATH_MAX + 8]; /* file:/abs/name */
} vid_Command;

/* Runs ffmpeg on the frames in the scratch directory work; ffmpeg writes
 * the film there (given as "file:" and an absolute path), and it is moved
 * to output (outputs.h) when ffmpeg exited 0 and the film is not empty.
 * EXIT_OK, EXIT_FAIL after a message, or cli_stop_status() after a signal. */
int vid_assemble(const char *work, double fps, const char *output, vid_Format f);
/* The ffmpeg command line that does the same by hand, shell-quoted. */
void vid_print_command(FILE *out, const char *frames_dir, double fps, const char *output, vid_Format f);

/* A new directory beside dir (dir.tmp-XXXXXX) to render frames into,
 * recorded for signals (*slot: release with cli_tmpdir_untrack). */
int vid_frames_tmpdir(const char *dir, char *tmp, size_t len, int *slot);
/* Moves count frames rendered in tmp_dir to dir: a rename when dir does not
 * exist; into it, replacing its older frames, when it does. */
int vid_publish_frames(const char *tmp_dir, const char *dir, int count);

#endif
