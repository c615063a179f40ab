/*
 * Synthetic Tracker experiments for the import tests: a known setup is
 * simulated with the library, filmed by a model camera (rolled, scaled,
 * optionally mirrored), tracked with Gaussian pixel noise, frame-time
 * jitter and missing frames, and written as Tracker writes it: a .trk file
 * (XMLControl) or an exported data table. The truth stays in memory for
 * the checks.
 *
 * The camera model here is written from Tracker's documentation of its
 * axes (image y down; world axes at an angle, counter-clockwise, in pixels
 * per metre), independently of cli/track/trk.c.
 */
#ifndef JC_TRACK_SYNTH_H
#define JC_TRACK_SYNTH_H

#include <jumpcyl/jumpcyl.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SYN_PI 3.14159265358979323846
#define SYN_MAX_MISSING 8

typedef struct {
    double fps;            /* frames per second of the tracked steps */
    int stepsize;          /* video frames per step (the video runs at fps * stepsize) */
    int startframe;        /* first video frame of the clip */
    double px_per_m;       /* camera scale */
    double roll_deg;       /* camera roll: the level lab x axis at this angle in the image */
    double cx_px, cy_px;   /* image of the lab origin (the contact point at the start) */
    double noise_px;       /* Gaussian pixel noise (per coordinate) */
    int jitter_fine;       /* table times off their nominal by up to this many twentieths of a frame */
    int mirror;            /* the ramp descends to the left in the image */
    int axes_incline;      /* Tracker's axes laid along the incline (else level) */
    double mark_offset_m;  /* the mark's distance from C, on the direction C -> G */
    long missing_centre[SYN_MAX_MISSING];
    int n_missing_centre;
    long missing_mark[SYN_MAX_MISSING];
    int n_missing_mark;
    uint64_t seed;
    /* The camera moved between two frames (a hand-held phone): from step
     * pan_from_step on, the image is shifted by (pan_dx_px, pan_dy_px), and
     * the .trk holds a key frame of the axes there (tables are unaffected:
     * Tracker exports world coordinates). 0: no move. */
    long pan_from_step;
    double pan_dx_px, pan_dy_px;
} syn_Camera;

/* The truth and the tracked pixels, per step. */
typedef struct {
    long n;
    double *t_s;             /* recorded time (jittered for tables) */
    double *x_m, *y_m;       /* true centre: along the incline, height */
    double *theta_rad, *omega_radps;
    double *cx_px, *cy_px;   /* tracked centre (NaN: missing) */
    double *mx_px, *my_px;   /* tracked mark (NaN: missing) */
    double radius_m, incline_rad;
    /* Tracker's coordinate system for these pixels */
    double origin_x_px, origin_y_px, axes_angle_deg, scale_px_per_m;
} syn_Experiment;

static inline double syn_uniform(uint64_t *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return (double)((*s * 2685821657736338717ull) >> 11) * (1.0 / 9007199254740992.0);
}

static inline double syn_gauss(uint64_t *s)
{
    double u = syn_uniform(s);
    while (u <= 0) u = syn_uniform(s);
    return sqrt(-2 * log(u)) * cos(2 * SYN_PI * syn_uniform(s));
}

static inline int syn_listed(const long *list, int n, long k)
{
    for (int i = 0; i < n; ++i)
        if (list[i] == k) return 1;
    return 0;
}

/* Lab (level, y up, metres) to image pixels (y down). */
static inline void syn_lab_to_image(const syn_Camera *c, double px, double py, double *ix, double *iy)
{
    const double r = c->roll_deg * SYN_PI / 180;
    *ix = c->cx_px + c->px_per_m * (cos(r) * px - sin(r) * py);
    *iy = c->cy_px - c->px_per_m * (sin(r) * px + cos(r) * py);
}

static inline void syn_free(syn_Experiment *e)
{
    double *arrays[] = {e->t_s, e->x_m, e->y_m, e->theta_rad, e->omega_radps, e->cx_px, e->cy_px, e->mx_px, e->my_px};
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; ++i) free(arrays[i]);
    memset(e, 0, sizeof *e);
}

/* Simulates the setup, samples every twentieth of a frame, films. 0 or -1. */
static inline int syn_make(const jc_Setup *setup, const syn_Camera *c, syn_Experiment *e)
{
    memset(e, 0, sizeof *e);
    jc_Model model;
    char err[256];
    if (jc_model_init(&model, setup, err, sizeof err) != JC_OK) {
        fprintf(stderr, "synth: %s\n", err);
        return -1;
    }
    jc_SimOptions o = jc_default_sim_options();
    const int fine = 20; /* samples per frame: jittered times fall on samples */
    o.sample_dt_s = 1.0 / (c->fps * fine);
    o.t_max_s = 3.0;
    jc_Run run;
    if (jc_simulate(&model, &o, &run, err, sizeof err) != JC_OK) {
        fprintf(stderr, "synth: %s\n", err);
        jc_run_free(&run);
        return -1;
    }
    /* The fixed samples only: k dt exactly (event samples have other times). */
    const double dt = o.sample_dt_s;
    long frames = 0;
    for (int i = 0; i < run.sample_count; ++i) {
        const double k = run.samples[i].state.t_s / dt;
        if (fabs(k - floor(k + 0.5)) < 1e-6 && (long)floor(k + 0.5) % fine == 0) frames++;
    }
    frames -= 1; /* room for a late jittered frame */
    const size_t bytes = (size_t)frames * sizeof(double);
    double **arrays[] = {&e->t_s, &e->x_m, &e->y_m, &e->theta_rad, &e->omega_radps,
                         &e->cx_px, &e->cy_px, &e->mx_px, &e->my_px};
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; ++i)
        if (!(*arrays[i] = malloc(bytes))) {
            jc_run_free(&run);
            syn_free(e);
            return -1;
        }
    /* The samples by index k of k dt. */
    long max_k = (long)(frames + 1) * fine;
    const jc_Sample **by_k = calloc((size_t)max_k + 1, sizeof *by_k);
    if (!by_k) {
        jc_run_free(&run);
        syn_free(e);
        return -1;
    }
    for (int i = 0; i < run.sample_count; ++i) {
        const double k = run.samples[i].state.t_s / dt;
        const long ki = (long)floor(k + 0.5);
        if (fabs(k - (double)ki) < 1e-6 && ki <= max_k && !by_k[ki]) by_k[ki] = &run.samples[i];
    }
    uint64_t s = c->seed * 0x9E3779B97F4A7C15ull + 1;
    const double a = setup->incline_rad, sg = c->mirror ? -1.0 : 1.0;
    const double xh[2] = {sg * cos(a), -sin(a)}, nh[2] = {sg * sin(a), cos(a)};
    e->n = frames;
    e->radius_m = setup->body.radius_m;
    e->incline_rad = a;
    for (long f = 0; f < frames; ++f) {
        long k = f * fine;
        if (c->jitter_fine > 0 && f > 0)
            k += (long)floor(syn_uniform(&s) * (2 * c->jitter_fine + 1)) - c->jitter_fine;
        const jc_Sample *p = by_k[k];
        if (!p) {
            fprintf(stderr, "synth: no sample at frame %ld\n", f);
            free(by_k);
            jc_run_free(&run);
            syn_free(e);
            return -1;
        }
        const jc_State *st = &p->state;
        e->t_s[f] = (double)k * dt;
        e->x_m[f] = st->x_m;
        e->y_m[f] = st->y_m;
        e->theta_rad[f] = st->theta_rad;
        e->omega_radps[f] = st->omega_radps;
        /* Incline frame (origin: the contact point at the start) to the lab. */
        const double X = st->x_m, Y = st->y_m;
        const double mX = X + c->mark_offset_m * sin(st->theta_rad), mY = Y + c->mark_offset_m * cos(st->theta_rad);
        double ix, iy;
        syn_lab_to_image(c, X * xh[0] + Y * nh[0], X * xh[1] + Y * nh[1], &ix, &iy);
        e->cx_px[f] = ix + c->noise_px * syn_gauss(&s);
        e->cy_px[f] = iy + c->noise_px * syn_gauss(&s);
        syn_lab_to_image(c, mX * xh[0] + mY * nh[0], mX * xh[1] + mY * nh[1], &ix, &iy);
        e->mx_px[f] = ix + c->noise_px * syn_gauss(&s);
        e->my_px[f] = iy + c->noise_px * syn_gauss(&s);
        if (c->pan_from_step > 0 && f >= c->pan_from_step) {
            e->cx_px[f] += c->pan_dx_px;
            e->cy_px[f] += c->pan_dy_px;
            e->mx_px[f] += c->pan_dx_px;
            e->my_px[f] += c->pan_dy_px;
        }
        if (syn_listed(c->missing_centre, c->n_missing_centre, f)) e->cx_px[f] = e->cy_px[f] = NAN;
        if (syn_listed(c->missing_mark, c->n_missing_mark, f)) e->mx_px[f] = e->my_px[f] = NAN;
    }
    free(by_k);
    jc_run_free(&run);
    /* Tracker's axes as a careful user sets them: the origin on the start's
     * contact point; x level (the camera's roll), or along the incline. */
    e->origin_x_px = c->cx_px;
    e->origin_y_px = c->cy_px;
    e->scale_px_per_m = c->px_per_m;
    const double incline_deg = a * 180 / SYN_PI;
    e->axes_angle_deg = c->roll_deg + (c->axes_incline ? (c->mirror ? incline_deg : -incline_deg) : 0.0);
    return 0;
}

/* Pixels to Tracker's world coordinates (metres), as Tracker's axes read them. */
static inline void syn_image_to_world(const syn_Experiment *e, double ix, double iy, double *wx, double *wy)
{
    const double b = e->axes_angle_deg * SYN_PI / 180;
    const double u = (ix - e->origin_x_px) / e->scale_px_per_m, v = -(iy - e->origin_y_px) / e->scale_px_per_m;
    *wx = cos(b) * u + sin(b) * v;
    *wy = -sin(b) * u + cos(b) * v;
}

static inline void syn_point_mass(FILE *f, const char *name, const syn_Camera *c, const syn_Experiment *e,
                                  const double *px, const double *py)
{
    fprintf(f,
            "        <property name=\"item\" type=\"object\">\n"
            "        <object class=\"org.opensourcephysics.cabrillo.tracker.PointMass\">\n"
            "            <property name=\"mass\" type=\"double\">1.0</property>\n"
            "            <property name=\"name\" type=\"string\">%s</property>\n"
            "            <property name=\"framedata\" type=\"array\" "
            "class=\"[Lorg.opensourcephysics.cabrillo.tracker.PointMass$FrameData;\">\n",
            name);
    for (long k = 0; k < e->n; ++k) {
        if (isnan(px[k])) continue;
        fprintf(f,
                "                <property name=\"[%ld]\" type=\"object\">\n"
                "                <object class=\"org.opensourcephysics.cabrillo.tracker.PointMass$FrameData\">\n"
                "                    <property name=\"x\" type=\"double\">%.17g</property>\n"
                "                    <property name=\"y\" type=\"double\">%.17g</property>\n"
                "                </object>\n"
                "                </property>\n",
                c->startframe + k * c->stepsize, px[k], py[k]);
    }
    fputs("            </property>\n        </object>\n        </property>\n", f);
}

/* One element of the axes' framedata array: the origin (px), angle and scale at frame index. */
static inline void syn_frame_data(char *buf, size_t len, long index, double origin_x_px, double origin_y_px,
                                  const syn_Experiment *e)
{
    snprintf(buf, len,
             "            <property name=\"[%ld]\" type=\"object\">\n"
             "            <object class=\"org.opensourcephysics.media.core.ImageCoordSystem$FrameData\">\n"
             "                <property name=\"xorigin\" type=\"double\">%.17g</property>\n"
             "                <property name=\"yorigin\" type=\"double\">%.17g</property>\n"
             "                <property name=\"angle\" type=\"double\">%.17g</property>\n"
             "                <property name=\"xscale\" type=\"double\">%.17g</property>\n"
             "                <property name=\"yscale\" type=\"double\">%.17g</property>\n"
             "            </object>\n"
             "            </property>\n",
             index, origin_x_px, origin_y_px, e->axes_angle_deg, e->scale_px_per_m, e->scale_px_per_m);
}

/* A .trk file as Tracker 6 writes one (the parts a reader needs, and some it does not). */
static inline int syn_write_trk(const char *path, const syn_Camera *c, const syn_Experiment *e,
                                const char *centre_name, const char *mark_name)
{
    FILE *f = fopen(path, "w");
    if (!f) return -1;
    const double video_dt_ms = 1000.0 / (c->fps * c->stepsize);
    /* The axes at frame 0, and a key frame where the camera moved (frame numbers index the array). */
    char first[1024], key[1024] = "";
    syn_frame_data(first, sizeof first, 0, e->origin_x_px, e->origin_y_px, e);
    if (c->pan_from_step > 0)
        syn_frame_data(key, sizeof key, c->startframe + c->pan_from_step * c->stepsize, e->origin_x_px + c->pan_dx_px,
                       e->origin_y_px + c->pan_dy_px, e);
    fprintf(f,
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
            "<object class=\"org.opensourcephysics.cabrillo.tracker.TrackerPanel\">\n"
            "    <property name=\"semantic_version\" type=\"string\">6.1.5</property>\n"
            "    <property name=\"width\" type=\"double\">1920.0</property>\n"
            "    <property name=\"height\" type=\"double\">1080.0</property>\n"
            "    <property name=\"videoclip\" type=\"object\">\n"
            "    <object class=\"org.opensourcephysics.media.core.VideoClip\">\n"
            "        <property name=\"video_framecount\" type=\"int\">%ld</property>\n"
            "        <property name=\"startframe\" type=\"int\">%d</property>\n"
            "        <property name=\"stepsize\" type=\"int\">%d</property>\n"
            "        <property name=\"stepcount\" type=\"int\">%ld</property>\n"
            "        <property name=\"starttime\" type=\"double\">0.0</property>\n"
            "        <property name=\"readout\" type=\"string\">frame</property>\n"
            "    </object>\n"
            "    </property>\n"
            "    <property name=\"clipcontrol\" type=\"object\">\n"
            "    <object class=\"org.opensourcephysics.media.core.StepperClipControl\">\n"
            "        <property name=\"rate\" type=\"double\">1.0</property>\n"
            "        <property name=\"delta_t\" type=\"double\">%.17g</property>\n"
            "        <property name=\"frame\" type=\"int\">0</property>\n"
            "    </object>\n"
            "    </property>\n"
            "    <property name=\"coords\" type=\"object\">\n"
            "    <object class=\"org.opensourcephysics.media.core.ImageCoordSystem\">\n"
            "        <property name=\"fixedorigin\" type=\"boolean\">true</property>\n"
            "        <property name=\"fixedangle\" type=\"boolean\">true</property>\n"
            "        <property name=\"fixedscale\" type=\"boolean\">true</property>\n"
            "        <property name=\"locked\" type=\"boolean\">false</property>\n"
            "        <property name=\"framedata\" type=\"array\" "
            "class=\"[Lorg.opensourcephysics.media.core.ImageCoordSystem$FrameData;\">\n"
            "%s%s"
            "        </property>\n"
            "    </object>\n"
            "    </property>\n"
            "    <property name=\"length_unit\" type=\"string\">m</property>\n"
            "    <property name=\"mass_unit\" type=\"string\">kg</property>\n"
            "    <property name=\"tracks\" type=\"collection\" class=\"java.util.ArrayList\">\n"
            "        <property name=\"item\" type=\"object\">\n"
            "        <object class=\"org.opensourcephysics.cabrillo.tracker.CoordAxes\">\n"
            "            <property name=\"name\" type=\"string\">axes</property>\n"
            "        </object>\n"
            "        </property>\n"
            "        <property name=\"item\" type=\"object\">\n"
            "        <object class=\"org.opensourcephysics.cabrillo.tracker.TapeMeasure\">\n"
            "            <property name=\"name\" type=\"string\">calibration stick</property>\n"
            "            <property name=\"worldlengths\" type=\"array\" class=\"[Ljava.lang.Double;\">\n"
            "                <property name=\"[0]\" type=\"double\">1.0</property>\n"
            "            </property>\n"
            "        </object>\n"
            "        </property>\n",
            c->startframe + e->n * c->stepsize + 10, c->startframe, c->stepsize, e->n, video_dt_ms, first, key);
    syn_point_mass(f, centre_name, c, e, e->cx_px, e->cy_px);
    if (mark_name) syn_point_mass(f, mark_name, c, e, e->mx_px, e->my_px);
    fputs("    </property>\n</object>\n", f);
    return fclose(f) == 0 ? 0 : -1;
}

/* A table as Tracker exports two tracks: "#multi:", the names row, the
 * header, rows with empty fields where a track has no position. delim is
 * '\t', ';' or ','; decimal_comma writes "0,123". */
static inline int syn_write_table(const char *path, const syn_Camera *c, const syn_Experiment *e,
                                  const char *centre_name, const char *mark_name, char delim, int decimal_comma)
{
    FILE *f = fopen(path, "w");
    if (!f) return -1;
    fprintf(f, "#multi:\n%c%s%c%c%s%c%c\n", delim, centre_name, delim, delim, mark_name, delim, delim);
    fprintf(f, "t%cx%cy%cx%cy%c\n", delim, delim, delim, delim, delim);
    for (long k = 0; k < e->n; ++k) {
        double v[5] = {e->t_s[k], NAN, NAN, NAN, NAN};
        const int moved = c->pan_from_step > 0 && k >= c->pan_from_step;
        const double px = moved ? c->pan_dx_px : 0, py = moved ? c->pan_dy_px : 0;
        if (!isnan(e->cx_px[k])) syn_image_to_world(e, e->cx_px[k] - px, e->cy_px[k] - py, &v[1], &v[2]);
        if (!isnan(e->mx_px[k])) syn_image_to_world(e, e->mx_px[k] - px, e->my_px[k] - py, &v[3], &v[4]);
        for (int i = 0; i < 5; ++i) {
            if (i) fputc(delim, f);
            if (isnan(v[i])) continue;
            char buf[64];
            snprintf(buf, sizeof buf, i == 0 ? "%.6f" : "%.9E", v[i]);
            if (decimal_comma)
                for (char *p = buf; *p; ++p)
                    if (*p == '.') *p = ',';
            fputs(buf, f);
        }
        fputc('\n', f);
    }
    return fclose(f) == 0 ? 0 : -1;
}

#endif
