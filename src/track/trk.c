/* Tracker's .trk files: the XMLControl format of Open Source Physics
 * (<object class=...><property name=... type=...>), read with libxml2.
 *
 * What is read (as Tracker 5 and 6 write it):
 *   TrackerPanel
 *     videoclip   VideoClip: startframe, stepsize, stepcount (steps are the
 *                 frames startframe + k stepsize); its video may hold delta_t
 *     clipcontrol ClipControl: delta_t, the frame duration in ms ("rate" is
 *                 the playback speed, not the frame rate)
 *     coords      ImageCoordSystem: framedata[frame] (xorigin, yorigin in
 *                 image pixels, angle in degrees, xscale, yscale in pixels per
 *                 world unit); only key frames are stored, a null entry keeps
 *                 the previous frame's values
 *     length_unit m, cm or mm
 *     tracks      PointMass: name, framedata[frame] (x, y: image pixels, y
 *                 down); TapeMeasure: worldlengths[0]
 * Tracker's image-to-world transform (ImageCoordSystem.updateTransforms) is
 * the inverse of: rotate the world point by the angle, scale (x by xscale, y
 * by -yscale), translate to the origin.
 *
 * Hostile files: no DTD is accepted (so no entity can be declared, let alone
 * expanded), the network is off, the file size is bounded by the caller, and
 * the tree libxml2 builds by a budget of elements, attributes and nodes
 * counted as it parses (TRK_MAX_*). */
#include "track_internal.h"

#include <stdio.h>
#include <errno.h>
#include <libxml/SAX2.h>
#include <libxml/xmlerror.h>
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The budget of the tree libxml2 builds, counted as it parses (trk_budget)
 * and stopped at the first count past its cap, so that a file of a million
 * empty elements costs what its first few hundred thousand do (about 100 MB
 * at most), not gigabytes. A frame of a track takes 4 elements, 7
 * attributes and about 25 nodes (elements, attributes, their values, text):
 * the caps allow some 30 000 frames of one track, or 7 500 of four (a
 * minute of 120 fps video), more than a clip of the kind the model
 * describes has. */
#define TRK_MAX_ELEMENTS 200000L
#define TRK_MAX_ATTRIBUTES 300000L
#define TRK_MAX_NODES 800000L

static const xmlChar *X(const char *s) { return (const xmlChar *)s; }

static int is_element(const xmlNode *n, const char *tag)
{
    return n && n->type == XML_ELEMENT_NODE && xmlStrcmp(n->name, X(tag)) == 0;
}

/* The <property name=NAME> child of an <object>, NULL if none. */
static xmlNode *prop(const xmlNode *obj, const char *name)
{
    if (!obj) return NULL;
    for (xmlNode *c = obj->children; c; c = c->next) {
        if (!is_element(c, "property")) continue;
        xmlChar *n = xmlGetProp(c, X("name"));
        const int same = n && xmlStrcmp(n, X(name)) == 0;
        xmlFree(n);
        if (same) return c;
    }
    return NULL;
}

/* The <object> held by a property, NULL if none. */
static xmlNode *prop_object(const xmlNode *p)
{
    if (!p) return NULL;
    for (xmlNode *c = p->children; c; c = c->next)
        if (is_element(c, "object")) return c;
    return NULL;
}

/* Whether an object's class is Tracker's or OSP's class SHORT (its name
 * after the last '.'). */
static int class_is(const xmlNode *obj, const char *short_name)
{
    xmlChar *cls = xmlGetProp(obj, X("class"));
    if (!cls) return 0;
    const char *s = (const char *)cls;
    const char *dot = strrchr(s, '.');
    const int same = strcmp(dot ? dot + 1 : s, short_name) == 0;
    xmlFree(cls);
    return same;
}

/* A property's text, trimmed, into buf. 1, 0 if absent, -1 if too long. */
static int prop_text(const xmlNode *obj, const char *name, char *buf, size_t len)
{
    const xmlNode *p = prop(obj, name);
    if (!p) return 0;
    xmlChar *text = xmlNodeGetContent(p);
    if (!text) return 0;
    const char *s = (const char *)text;
    while (*s == ' ' || *s == '\t' || *s == '\n' || *s == '\r') s++;
    size_t n = strlen(s);
    while (n > 0 && (s[n - 1] == ' ' || s[n - 1] == '\t' || s[n - 1] == '\n' || s[n - 1] == '\r')) n--;
    int st = 1;
    if (n >= len) st = -1;
    else {
        memcpy(buf, s, n);
        buf[n] = '\0';
    }
    xmlFree(text);
    return st;
}

typedef struct {
    const char *file;
    char *err;
    size_t err_len;
} trk_ctx;

/* A finite number: 1, 0 if absent, -1 after a message. */
static int prop_double(const trk_ctx *c, const xmlNode *obj, const char *what, const char *name, double *out)
{
    char buf[64];
    const int st = prop_text(obj, name, buf, sizeof buf);
    if (st == 0) return 0;
    char *end = NULL;
    errno = 0;
    const double v = st > 0 ? strtod(buf, &end) : NAN;
    if (st < 0 || end == buf || *end != '\0' || !isfinite(v) || errno == ERANGE) {
        snprintf(c->err, c->err_len, "%s: %s: %s is not a finite number", c->file, what, name);
        return -1;
    }
    *out = v;
    return 1;
}

static int prop_long(const trk_ctx *c, const xmlNode *obj, const char *what, const char *name, long *out)
{
    double v = 0;
    const int st = prop_double(c, obj, what, name, &v);
    if (st <= 0) return st;
    if (v != floor(v) || fabs(v) > (double)JC_TRACK_MAX_FRAMES * 16) {
        snprintf(c->err, c->err_len, "%s: %s: %s is not a whole number in range", c->file, what, name);
        return -1;
    }
    *out = (long)v;
    return 1;
}

/* The index of an array item named "[N]"; -1 if the name is not that. */
static long item_index(const xmlNode *item)
{
    xmlChar *n = xmlGetProp(item, X("name"));
    long idx = -1;
    if (n) {
        const char *s = (const char *)n;
        size_t len = strlen(s);
        if (len >= 3 && len <= 9 && s[0] == '[' && s[len - 1] == ']') {
            idx = 0;
            for (size_t i = 1; i + 1 < len; ++i) {
                if (s[i] < '0' || s[i] > '9') { idx = -1; break; }
                idx = idx * 10 + (s[i] - '0');
            }
        }
    }
    xmlFree(n);
    return idx;
}

/* The clip: which frames are steps and how long a frame lasts. */
typedef struct {
    long start, step, count;
    double dt_s;
    double width_px, height_px; /* the picture's size (0 when the file does not say) */
} trk_clip;

/* How far outside the picture a point or an origin may lie (pixels): far
 * enough for any real clip, near enough that no digit is lost. */
#define TRK_MAX_OUTSIDE_PX 1e6

/* Whether an image point lies within TRK_MAX_OUTSIDE_PX of the picture. */
static int in_picture(const trk_clip *clip, double x_px, double y_px)
{
    return x_px >= -TRK_MAX_OUTSIDE_PX && x_px <= clip->width_px + TRK_MAX_OUTSIDE_PX &&
           y_px >= -TRK_MAX_OUTSIDE_PX && y_px <= clip->height_px + TRK_MAX_OUTSIDE_PX;
}

static void outside_message(const trk_ctx *c, const trk_clip *clip, const char *what, const char *names, double x_px,
                            double y_px)
{
    snprintf(c->err, c->err_len,
             "%s: %s: %s (%.6g, %.6g) px, more than %g px outside the %g x %g px picture (refused)", c->file,
             what, names, x_px, y_px, TRK_MAX_OUTSIDE_PX, clip->width_px, clip->height_px);
}

static long max_item_index(const xmlNode *array)
{
    long max = -1;
    if (!array) return max;
    for (xmlNode *c = array->children; c; c = c->next)
        if (is_element(c, "property")) {
            const long i = item_index(c);
            if (i > max) max = i;
        }
    return max;
}

static int read_clip(const trk_ctx *c, const xmlNode *panel, const xmlNode *first_track_data, trk_clip *clip)
{
    const xmlNode *vc = prop_object(prop(panel, "videoclip"));
    clip->start = 0;
    clip->step = 1;
    clip->count = -1;
    clip->width_px = clip->height_px = 0;
    double size[2] = {0, 0};
    if (prop_double(c, panel, "TrackerPanel", "width", &size[0]) < 0 ||
        prop_double(c, panel, "TrackerPanel", "height", &size[1]) < 0)
        return -1;
    if (size[0] > 0 && size[0] <= TRK_MAX_OUTSIDE_PX) clip->width_px = size[0];
    if (size[1] > 0 && size[1] <= TRK_MAX_OUTSIDE_PX) clip->height_px = size[1];
    if (vc) {
        if (prop_long(c, vc, "videoclip", "startframe", &clip->start) < 0) return -1;
        if (prop_long(c, vc, "videoclip", "stepsize", &clip->step) < 0) return -1;
        if (prop_long(c, vc, "videoclip", "stepcount", &clip->count) < 0) return -1;
    }
    if (clip->count < 0) /* no clip: every frame a track has */
        clip->count = first_track_data ? max_item_index(first_track_data) + 1 : 0;
    if (clip->start < 0 || clip->step < 1 || clip->count < 1 || clip->count > JC_TRACK_MAX_FRAMES ||
        clip->step > JC_TRACK_MAX_FRAMES || clip->start + (clip->count - 1) * clip->step >= 16 * JC_TRACK_MAX_FRAMES) {
        snprintf(c->err, c->err_len,
                 "%s: videoclip: startframe %ld, stepsize %ld, stepcount %ld (need startframe >= 0, stepsize >= 1, "
                 "1 to %ld steps)",
                 c->file, clip->start, clip->step, clip->count, JC_TRACK_MAX_FRAMES);
        return -1;
    }
    double dt_ms = NAN;
    int st = prop_double(c, prop_object(prop(panel, "clipcontrol")), "clipcontrol", "delta_t", &dt_ms);
    if (st < 0) return -1;
    if (st == 0) st = prop_double(c, prop_object(prop(vc, "video")), "video", "delta_t", &dt_ms);
    if (st < 0) return -1;
    if (st == 0) {
        snprintf(c->err, c->err_len, "%s: no frame duration (clipcontrol delta_t)", c->file);
        return -1;
    }
    if (!(dt_ms > 1e-6 && dt_ms < 1e7)) {
        snprintf(c->err, c->err_len, "%s: clipcontrol: delta_t %g ms is not a frame duration", c->file, dt_ms);
        return -1;
    }
    clip->dt_s = dt_ms / 1000.0;
    return 0;
}

/* The coordinate system for every frame up to last: key frames carried forward. */
typedef struct {
    double *ox, *oy, *cos_a, *sin_a, *sx, *sy;
} trk_coords;

static void coords_free(trk_coords *k)
{
    free(k->ox);
    free(k->oy);
    free(k->cos_a);
    free(k->sin_a);
    free(k->sx);
    free(k->sy);
}

static int read_coords(const trk_ctx *c, const xmlNode *panel, const trk_clip *clip, long frames, trk_coords *k,
                       int *varies)
{
    const xmlNode *cs = prop_object(prop(panel, "coords"));
    const xmlNode *fd = prop(cs, "framedata");
    if (!cs || !fd) {
        snprintf(c->err, c->err_len, "%s: no coordinate system (coords framedata)", c->file);
        return -1;
    }
    double **arrays[6] = {&k->ox, &k->oy, &k->cos_a, &k->sin_a, &k->sx, &k->sy};
    for (int i = 0; i < 6; ++i) {
        *arrays[i] = malloc((size_t)frames * sizeof(double));
        if (!*arrays[i]) {
            snprintf(c->err, c->err_len, "%s: out of memory", c->file);
            return JC_ENOMEM;
        }
        for (long f = 0; f < frames; ++f) (*arrays[i])[f] = NAN;
    }
    for (xmlNode *it = fd->children; it; it = it->next) {
        if (!is_element(it, "property")) continue;
        const long f = item_index(it);
        const xmlNode *o = prop_object(it);
        if (f < 0 || !o) continue; /* a null entry: not a key frame */
        if (f >= frames) continue;
        double v[5];
        const char *names[5] = {"xorigin", "yorigin", "angle", "xscale", "yscale"};
        for (int i = 0; i < 5; ++i) {
            const int st = prop_double(c, o, "coords framedata", names[i], &v[i]);
            if (st < 0) return -1;
            if (st == 0) {
                snprintf(c->err, c->err_len, "%s: coords framedata [%ld]: no %s", c->file, f, names[i]);
                return -1;
            }
        }
        if (!in_picture(clip, v[0], v[1])) {
            char what[64];
            snprintf(what, sizeof what, "coords framedata [%ld]", f);
            outside_message(c, clip, what, "the origin", v[0], v[1]);
            return -1;
        }
        if (!(v[3] > 1e-9 && v[4] > 1e-9 && v[3] < 1e12 && v[4] < 1e12)) {
            snprintf(c->err, c->err_len, "%s: coords framedata [%ld]: scale %g, %g px per unit (must be > 0)", c->file,
                     f, v[3], v[4]);
            return -1;
        }
        const double a = v[2] * JC_TRACK_PI / 180.0;
        k->ox[f] = v[0];
        k->oy[f] = v[1];
        k->cos_a[f] = cos(a);
        k->sin_a[f] = sin(a);
        k->sx[f] = v[3];
        k->sy[f] = v[4];
    }
    if (isnan(k->ox[0])) {
        snprintf(c->err, c->err_len, "%s: coords framedata has no frame 0", c->file);
        return -1;
    }
    *varies = 0;
    for (long f = 1; f < frames; ++f) {
        if (isnan(k->ox[f])) {
            for (int i = 0; i < 6; ++i) (*arrays[i])[f] = (*arrays[i])[f - 1];
        } else {
            for (int i = 0; i < 6; ++i)
                if ((*arrays[i])[f] != (*arrays[i])[f - 1]) *varies = 1;
        }
    }
    return 0;
}

static int count_point_masses(const xmlNode *tracks)
{
    int n = 0;
    if (!tracks) return 0;
    for (xmlNode *it = tracks->children; it; it = it->next) {
        const xmlNode *o = is_element(it, "property") ? prop_object(it) : NULL;
        if (o && class_is(o, "PointMass")) n++;
    }
    return n;
}

static int read_track(const trk_ctx *c, const xmlNode *o, const trk_clip *clip, const trk_coords *k,
                      double m_per_unit, jc_TrackRaw *raw, int ti)
{
    jc_TrackPoints *t = &raw->tracks[ti];
    char name[JC_TRACK_NAME_LEN];
    const int st = prop_text(o, "name", name, sizeof name);
    if (st < 0) {
        snprintf(c->err, c->err_len, "%s: a track's name is longer than %d bytes", c->file, JC_TRACK_NAME_LEN - 1);
        return -1;
    }
    if (st == 0 || !name[0]) snprintf(name, sizeof name, "mass %c", 'A' + ti);
    for (char *p = name; *p; ++p)
        if ((unsigned char)*p < 0x20 || *p == 0x7f) *p = '?'; /* names go to one-line reports */
    strcpy(t->name, name);
    const xmlNode *fd = prop(o, "framedata");
    if (!fd) return 0; /* a track with no position yet */
    const long last = clip->start + (clip->count - 1) * clip->step;
    for (xmlNode *it = fd->children; it; it = it->next) {
        if (!is_element(it, "property")) continue;
        const long f = item_index(it);
        const xmlNode *p = prop_object(it);
        if (f < 0 || !p || f < clip->start || f > last || (f - clip->start) % clip->step != 0) continue;
        double ix = NAN, iy = NAN;
        char what[JC_TRACK_NAME_LEN + 96];
        snprintf(what, sizeof what, "track '%s' frame %ld", t->name, f);
        const int sx = prop_double(c, p, what, "x", &ix), sy = prop_double(c, p, what, "y", &iy);
        if (sx < 0 || sy < 0) return -1;
        if (sx == 0 || sy == 0) {
            snprintf(c->err, c->err_len, "%s: %s: no %s", c->file, what, sx == 0 ? "x" : "y");
            return -1;
        }
        if (!in_picture(clip, ix, iy)) {
            outside_message(c, clip, what, "x, y", ix, iy);
            return -1;
        }
        const double u = (ix - k->ox[f]) / k->sx[f], v = -(iy - k->oy[f]) / k->sy[f];
        const long row = (f - clip->start) / clip->step;
        t->x_m[row] = (k->cos_a[f] * u + k->sin_a[f] * v) * m_per_unit;
        t->y_m[row] = (-k->sin_a[f] * u + k->cos_a[f] * v) * m_per_unit;
    }
    return 0;
}

/* Whether a declaration "<!NAME" (needle without its "<!") is in data:
 * found by its '!', which is rare in XML, not by '<', which is not. */
static int has_declaration(const char *data, size_t len, const char *needle)
{
    const size_t n = strlen(needle);
    for (const char *p = data, *end = data + len; (p = memchr(p, '!', (size_t)(end - p))) != NULL; ++p)
        if (p > data && p[-1] == '<' && (size_t)(end - p - 1) >= n && memcmp(p + 1, needle, n) == 0) return 1;
    return 0;
}

/* What the parser has built so far, against the caps; the parser's own
 * callbacks (libxml2's SAX2 tree builder) are called only within them. */
typedef struct {
    long elements, attributes, nodes;
    const char *over; /* the count past its cap ("elements", ...), NULL within */
    int no_memory;    /* libxml2 ran out of memory (its errors come here, not to stderr) */
    long cap;
    xmlSAXHandler sax2; /* libxml2's tree builder, called on */
} trk_budget;

/* Adds to the counts; 0 within the caps, else -1 and the parser stopped. */
static int budget_take(void *ctx, long elements, long attributes, long nodes)
{
    xmlParserCtxt *ctxt = ctx;
    trk_budget *b = ctxt->_private;
    if (b->over) return -1;
    b->elements += elements;
    b->attributes += attributes;
    b->nodes += nodes;
    if (b->elements > TRK_MAX_ELEMENTS) b->over = "elements", b->cap = TRK_MAX_ELEMENTS;
    else if (b->attributes > TRK_MAX_ATTRIBUTES) b->over = "attributes", b->cap = TRK_MAX_ATTRIBUTES;
    else if (b->nodes > TRK_MAX_NODES) b->over = "nodes", b->cap = TRK_MAX_NODES;
    if (!b->over) return 0;
    xmlStopParser(ctxt);
    return -1;
}

static void budget_start(void *ctx, const xmlChar *localname, const xmlChar *prefix, const xmlChar *uri,
                         int nb_namespaces, const xmlChar **namespaces, int nb_attributes, int nb_defaulted,
                         const xmlChar **attributes)
{
    /* An element, its attributes and each attribute's value. */
    if (budget_take(ctx, 1, nb_attributes, 1 + 2L * nb_attributes + nb_namespaces) != 0) return;
    const trk_budget *b = ((xmlParserCtxt *)ctx)->_private;
    b->sax2.startElementNs(ctx, localname, prefix, uri, nb_namespaces, namespaces, nb_attributes, nb_defaulted,
                           attributes);
}

static void budget_characters(void *ctx, const xmlChar *ch, int len)
{
    if (budget_take(ctx, 0, 0, 1) != 0) return;
    ((trk_budget *)((xmlParserCtxt *)ctx)->_private)->sax2.characters(ctx, ch, len);
}

static void budget_whitespace(void *ctx, const xmlChar *ch, int len)
{
    if (budget_take(ctx, 0, 0, 1) != 0) return;
    ((trk_budget *)((xmlParserCtxt *)ctx)->_private)->sax2.ignorableWhitespace(ctx, ch, len);
}

static void budget_cdata(void *ctx, const xmlChar *ch, int len)
{
    if (budget_take(ctx, 0, 0, 1) != 0) return;
    ((trk_budget *)((xmlParserCtxt *)ctx)->_private)->sax2.cdataBlock(ctx, ch, len);
}

static void budget_comment(void *ctx, const xmlChar *value)
{
    if (budget_take(ctx, 0, 0, 1) != 0) return;
    ((trk_budget *)((xmlParserCtxt *)ctx)->_private)->sax2.comment(ctx, value);
}

static void budget_pi(void *ctx, const xmlChar *target, const xmlChar *data)
{
    if (budget_take(ctx, 0, 0, 1) != 0) return;
    ((trk_budget *)((xmlParserCtxt *)ctx)->_private)->sax2.processingInstruction(ctx, target, data);
}

/* The file's bytes handed to the parser a piece at a time. */
typedef struct {
    const char *data;
    size_t left;
} trk_source;

static int source_read(void *ctx, char *buf, int len)
{
    trk_source *src = ctx;
    const size_t n = src->left < (size_t)len ? src->left : (size_t)len;
    memcpy(buf, src->data, n);
    src->data += n;
    src->left -= n;
    return (int)n;
}

/* The parser's errors: kept in the context (xmlCtxtGetLastError) as ever,
 * and a memory failure noted, as a later error may replace it there. */
static void budget_error(void *ctx, xmlError *e)
{
    trk_budget *b = ((xmlParserCtxt *)ctx)->_private;
    if (e && e->code == XML_ERR_NO_MEMORY) b->no_memory = 1;
}

/* Errors libxml2 reports outside a parser context (the tree's allocations):
 * not printed, as the library prints nothing; their reason is memory. */
static void quiet_generic_error(void *ctx, const char *msg, ...)
{
    trk_budget *b = ctx;
    (void)msg;
    b->no_memory = 1;
}

/* Puts the counting callbacks in front of the tree builder's. */
static void budget_install(xmlParserCtxt *ctxt, trk_budget *b)
{
    memset(b, 0, sizeof *b);
    b->sax2 = *ctxt->sax;
    ctxt->_private = b;
    ctxt->sax->serror = budget_error;
    if (b->sax2.startElementNs) ctxt->sax->startElementNs = budget_start;
    if (b->sax2.characters) ctxt->sax->characters = budget_characters;
    if (b->sax2.ignorableWhitespace) ctxt->sax->ignorableWhitespace = budget_whitespace;
    if (b->sax2.cdataBlock) ctxt->sax->cdataBlock = budget_cdata;
    if (b->sax2.comment) ctxt->sax->comment = budget_comment;
    if (b->sax2.processingInstruction) ctxt->sax->processingInstruction = budget_pi;
}

static int parse_doc(const trk_ctx *c, xmlDoc *doc, jc_TrackRaw *raw)
{
    const xmlNode *panel = xmlDocGetRootElement(doc);
    if (!is_element(panel, "object") || !class_is(panel, "TrackerPanel")) {
        snprintf(c->err, c->err_len, "%s: not a Tracker file (the root is not a TrackerPanel object)", c->file);
        return -1;
    }
    char unit[16] = "m";
    if (prop_text(panel, "length_unit", unit, sizeof unit) < 0) unit[0] = '?';
    const double m_per_unit = strcmp(unit, "m") == 0 ? 1.0 : strcmp(unit, "cm") == 0 ? 0.01
                              : strcmp(unit, "mm") == 0 ? 0.001 : NAN;
    if (isnan(m_per_unit)) {
        snprintf(c->err, c->err_len, "%s: length_unit is not m, cm or mm", c->file);
        return -1;
    }
    const xmlNode *tracks = prop(panel, "tracks");
    const int n_pm = count_point_masses(tracks);
    if (n_pm == 0) {
        snprintf(c->err, c->err_len, "%s: no point-mass track", c->file);
        return -1;
    }
    if (n_pm > JC_TRACK_MAX_TRACKS) {
        snprintf(c->err, c->err_len, "%s: %d point-mass tracks (at most %d)", c->file, n_pm, JC_TRACK_MAX_TRACKS);
        return -1;
    }
    const xmlNode *first_data = NULL;
    for (xmlNode *it = tracks->children; it && !first_data; it = it->next) {
        const xmlNode *o = is_element(it, "property") ? prop_object(it) : NULL;
        if (o && class_is(o, "PointMass")) first_data = prop(o, "framedata");
    }
    trk_clip clip;
    if (read_clip(c, panel, first_data, &clip) != 0) return -1;
    const long frames_total = clip.start + (clip.count - 1) * clip.step + 1;
    trk_coords k = {0};
    const int coords = read_coords(c, panel, &clip, frames_total, &k, &raw->scale_varies);
    if (coords != 0) {
        coords_free(&k);
        return coords;
    }
    if (jc_track_raw_alloc(raw, clip.count, n_pm) != JC_OK) {
        snprintf(c->err, c->err_len, "%s: out of memory", c->file);
        coords_free(&k);
        return JC_ENOMEM;
    }
    raw->px_per_m = k.sx[clip.start] / m_per_unit;
    raw->nominal_dt_s = clip.dt_s * (double)clip.step; /* between steps */
    for (long i = 0; i < clip.count; ++i) raw->t_s[i] = (double)(i * clip.step) * clip.dt_s;
    int ti = 0, st = 0;
    for (xmlNode *it = tracks->children; it && st == 0; it = it->next) {
        const xmlNode *o = is_element(it, "property") ? prop_object(it) : NULL;
        if (!o) continue;
        if (class_is(o, "PointMass")) st = read_track(c, o, &clip, &k, m_per_unit, raw, ti++);
        else if (class_is(o, "TapeMeasure") && isnan(raw->tape_length_m)) {
            const xmlNode *wl = prop(o, "worldlengths");
            const xmlNode *first = NULL;
            for (xmlNode *w = wl ? wl->children : NULL; w && !first; w = w->next)
                if (is_element(w, "property") && item_index(w) == 0) first = w;
            if (first) {
                xmlChar *text = xmlNodeGetContent(first);
                char *end = NULL;
                const double v = text ? strtod((const char *)text, &end) : NAN;
                if (text && end != (const char *)text && isfinite(v) && v > 0) raw->tape_length_m = v * m_per_unit;
                xmlFree(text);
            }
        }
    }
    coords_free(&k);
    return st;
}

int jc_track_trk_parse(const char *name, const char *data, size_t len, jc_TrackRaw *raw, char *err, size_t err_len)
{
    memset(raw, 0, sizeof *raw);
    raw->px_per_m = raw->tape_length_m = raw->nominal_dt_s = NAN;
    strcpy(raw->format, "trk");
    if (err_len > 0) err[0] = '\0';
    const trk_ctx c = {name, err, err_len};
    /* libxml2 takes an int length; the caller's bound is far below. */
    if (len > (size_t)JC_TRACK_MAX_BYTES) {
        snprintf(err, err_len, "%s: too large", name);
        return JC_EINVAL;
    }
    /* A DTD is where entities are declared: refused before libxml2 reads it. */
    if (has_declaration(data, len, "DOCTYPE") || has_declaration(data, len, "ENTITY")) {
        snprintf(err, err_len, "%s: has a DTD or entity declaration (refused)", name);
        return JC_EINVAL;
    }
    xmlParserCtxt *ctxt = xmlNewParserCtxt();
    if (!ctxt) {
        snprintf(err, err_len, "%s: out of memory", name);
        return JC_ENOMEM;
    }
    trk_budget budget;
    budget_install(ctxt, &budget);
    /* Fed in pieces (xmlCtxtReadMemory would copy the whole file first);
     * no network, no entity substitution, no DTD loading, no huge text
     * nodes; short strings kept in their nodes (COMPACT: less memory). */
    trk_source src = {data, len};
    /* The generic error handler is this thread's: ours for the parse only. */
    xmlGenericErrorFunc old_handler = xmlGenericError;
    void *old_handler_ctx = xmlGenericErrorContext;
    xmlSetGenericErrorFunc(&budget, quiet_generic_error);
    xmlDoc *doc = xmlCtxtReadIO(ctxt, source_read, NULL, &src, NULL, NULL,
                                XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING | XML_PARSE_COMPACT);
    xmlSetGenericErrorFunc(old_handler_ctx, old_handler);
    const xmlError *e = xmlCtxtGetLastError(ctxt);
    int st = -1;
    if (budget.over) {
        snprintf(err, err_len,
                 "%s: line %d: more than %ld XML %s, where the reading stopped (%ld elements, %ld attributes, "
                 "%ld nodes; allowed: %ld, %ld, %ld, some 30000 frames of one track)",
                 name, xmlSAX2GetLineNumber(ctxt), budget.cap, budget.over, budget.elements, budget.attributes,
                 budget.nodes, TRK_MAX_ELEMENTS, TRK_MAX_ATTRIBUTES, TRK_MAX_NODES);
    } else if (budget.no_memory || ctxt->errNo == XML_ERR_NO_MEMORY || (e && e->code == XML_ERR_NO_MEMORY)) {
        snprintf(err, err_len, "%s: out of memory reading its XML (%ld elements, %ld nodes so far)", name,
                 budget.elements, budget.nodes);
        st = JC_ENOMEM;
    } else if (!doc) {
        char msg[160] = "not well-formed XML";
        if (e && e->message) {
            snprintf(msg, sizeof msg, "%s", e->message);
            for (char *p = msg; *p; ++p)
                if (*p == '\n' || *p == '\r') *p = '\0';
        }
        snprintf(err, err_len, "%s: line %d: %s", name, e ? e->line : 0, msg);
    } else if (doc->intSubset || doc->extSubset) {
        snprintf(err, err_len, "%s: has a DTD (refused)", name);
    } else {
        st = parse_doc(&c, doc, raw);
    }
    if (doc) xmlFreeDoc(doc);
    xmlFreeParserCtxt(ctxt);
    if (st == 0) return JC_OK;
    jc_track_raw_free(raw);
    return st == JC_ENOMEM ? JC_ENOMEM : JC_EINVAL;
}
