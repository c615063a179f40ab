/*
 * The WebAssembly entry point: one setup in (a JSON object whose keys are
 * the command line's option names), one run out (a JSON document with the
 * events, the sampled trajectory, the termination and the first lift-off).
 * A thin client of the public API (include/jumpcyl/jumpcyl.h): it builds a
 * jc_Setup the way the jumpcyl tool does (cli/commands/options.c), then
 * jc_model_init, jc_simulate (as `jumpcyl simulate`), jc_run_summarize.
 *
 * Numbers are the command line's plain numbers: SI units, angles in
 * degrees (incline, theta0, a part's angle), omega0 in rad/s. Unit strings
 * ("10cm") are not read here: the page converts. docs/web.md lists the keys.
 *
 * Every returned string is malloc'd and owned by the caller: free it with
 * jc_web_free. A bad request gives {"ok": false, "error": "..."} (one
 * line), never an abort. NULL only when memory ran out.
 *
 * No global mutable state; the only process-wide setting touched is GSL's
 * error handler, switched off as the library's header asks.
 */
#include <cjson/cJSON.h>
#include <gsl/gsl_errno.h>
#include <jumpcyl/jumpcyl.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef __EMSCRIPTEN__
#include <emscripten/emscripten.h>
#define JC_WEB_EXPORT EMSCRIPTEN_KEEPALIVE
#else
#define JC_WEB_EXPORT
#endif

/* The declarations, for -Wmissing-prototypes (the JS side calls these). */
JC_WEB_EXPORT char *jc_web_simulate(const char *request_json);
JC_WEB_EXPORT char *jc_web_presets(void);
JC_WEB_EXPORT const char *jc_web_version(void);
JC_WEB_EXPORT void jc_web_free(char *text);

#define WEB_PI 3.14159265358979323846 /* the tool's CLI_PI: degrees convert exactly as there */
#define WEB_DEFAULT_MAX_SAMPLES 100000 /* the library's default is 10^6: too much JSON for a page */
#define ERR_LEN 512

/* ---- the request ---- */

/* The scalar setup options, as in the tool's table (options.c "scalars"). */
typedef struct {
    const char *name;
    size_t field;
} scalar_opt;

static const scalar_opt scalars[] = {
    {"incline", offsetof(jc_Setup, incline_rad)},
    {"g", offsetof(jc_Setup, gravity_mps2)},
    {"mu", offsetof(jc_Setup, mu_static)},
    {"mu-s", offsetof(jc_Setup, mu_static)},
    {"mu-k", offsetof(jc_Setup, mu_kinetic)},
    {"restitution", offsetof(jc_Setup, restitution)},
    {"theta0", offsetof(jc_Setup, theta0_rad)},
    {"omega0", offsetof(jc_Setup, omega0_radps)},
    {"ramp-length", offsetof(jc_Setup, ramp_length_m)},
    {"paper-d", offsetof(jc_Setup, paper_cm_offset_m)},
    {"length", offsetof(jc_Setup, length_m)},
    {"air-density", offsetof(jc_Setup, air_density_kgpm3)},
    {"drag-coefficient", offsetof(jc_Setup, drag_coefficient)},
    {"lift-coefficient", offsetof(jc_Setup, lift_coefficient)},
    {"spin-drag", offsetof(jc_Setup, spin_drag_Nms2)},
    {"rolling-resistance", offsetof(jc_Setup, rolling_resistance_m)},
};

/* Every key a request may hold; anything else is refused by name. */
static const char *const known_keys[] = {
    "preset", "part", "radius", "disc-mass", "rod-mass", "rod-offset", "rod-radius", "impact-law",
    "incline", "g", "mu", "mu-s", "mu-k", "restitution", "theta0", "omega0", "ramp-length", "paper-d",
    "length", "air-density", "drag-coefficient", "lift-coefficient", "spin-drag", "rolling-resistance",
    "t-max", "max-events", "sample-dt", "max-samples", "rtol", "atol", "event-tol", "contact-height"};

static int is_angle(const char *name)
{
    return strcmp(name, "incline") == 0 || strcmp(name, "theta0") == 0;
}

/* A number member: 0 absent, 1 read into *out, -1 not a finite number. */
static int get_number(const cJSON *req, const char *name, double *out, char *err, size_t err_len)
{
    const cJSON *item = cJSON_GetObjectItemCaseSensitive(req, name);
    if (!item) return 0;
    if (!cJSON_IsNumber(item) || !isfinite(item->valuedouble)) {
        snprintf(err, err_len, "'%s' must be a number", name);
        return -1;
    }
    *out = item->valuedouble;
    return 1;
}

static int get_string(const cJSON *req, const char *name, const char **out, char *err, size_t err_len)
{
    const cJSON *item = cJSON_GetObjectItemCaseSensitive(req, name);
    if (!item) return 0;
    if (!cJSON_IsString(item)) {
        snprintf(err, err_len, "'%s' must be a string", name);
        return -1;
    }
    *out = item->valuestring;
    return 1;
}

static int check_keys(const cJSON *req, char *err, size_t err_len)
{
    for (const cJSON *it = req->child; it; it = it->next) {
        size_t k = 0;
        const size_t n = sizeof known_keys / sizeof known_keys[0];
        while (k < n && strcmp(it->string, known_keys[k]) != 0) ++k;
        if (k == n) {
            snprintf(err, err_len, "unknown option '%.60s' (the keys are the command line's option names, docs/web.md)",
                     it->string);
            return -1;
        }
        for (const cJSON *jt = it->next; jt; jt = jt->next)
            if (strcmp(it->string, jt->string) == 0) {
                snprintf(err, err_len, "'%s' given twice", it->string);
                return -1;
            }
    }
    return 0;
}

static int parse_kind(const char *name, jc_PartKind *kind)
{
    static const jc_PartKind kinds[] = {JC_PART_DISC, JC_PART_HOOP, JC_PART_ROD, JC_PART_POINT};
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; ++k)
        if (strcmp(name, jc_part_kind_name(kinds[k])) == 0) {
            *kind = kinds[k];
            return 0;
        }
    return -1;
}

/* {"kind": "rod", "mass": 0.0321, "offset": 0.055, "radius": 0.00475, "angle": 0}
 * as the tool's --part rod:mass=...: mass required, disc and hoop radius
 * defaulting to the rim, angle in degrees. */
static int parse_part(const cJSON *o, int i, double rim_m, jc_Part *p, char *err, size_t err_len)
{
    const cJSON *kind = cJSON_GetObjectItemCaseSensitive(o, "kind");
    if (!cJSON_IsObject(o) || !cJSON_IsString(kind) || parse_kind(kind->valuestring, &p->kind) != 0) {
        snprintf(err, err_len, "part %d: needs \"kind\": disc, hoop, rod or point", i + 1);
        return -1;
    }
    *p = (jc_Part){p->kind, 0.0, 0.0, 0.0, 0.0};
    if (p->kind == JC_PART_DISC || p->kind == JC_PART_HOOP) p->radius_m = rim_m;
    static const char *const keys[] = {"kind", "mass", "offset", "radius", "angle"};
    for (const cJSON *it = o->child; it; it = it->next) {
        size_t k = 0;
        while (k < 5 && strcmp(it->string, keys[k]) != 0) ++k;
        if (k == 5) {
            snprintf(err, err_len, "part %d: unknown key '%.40s' (allowed: kind, mass, offset, radius, angle)", i + 1,
                     it->string);
            return -1;
        }
        if (k == 0) continue;
        if (!cJSON_IsNumber(it) || !isfinite(it->valuedouble)) {
            snprintf(err, err_len, "part %d: '%s' must be a number", i + 1, keys[k]);
            return -1;
        }
        const double v = it->valuedouble;
        if (k == 1) p->mass_kg = v;
        else if (k == 2) p->offset_m = v;
        else if (k == 3) p->radius_m = v;
        else p->angle_rad = v * (WEB_PI / 180.0);
    }
    if (!cJSON_GetObjectItemCaseSensitive(o, "mass")) {
        snprintf(err, err_len, "part %d: mass is required", i + 1);
        return -1;
    }
    return 0;
}

static jc_Part *find_part(jc_BodyDef *b, jc_PartKind kind)
{
    for (int i = 0; i < b->part_count; ++i)
        if (b->parts[i].kind == kind) return &b->parts[i];
    return NULL;
}

/* The body: preset, then parts, then the radius and disc+rod shortcuts. */
static int build_body(const cJSON *req, jc_Setup *s, int *body_changed, char *err, size_t err_len)
{
    double r = s->body.radius_m, v;
    int have_r = get_number(req, "radius", &r, err, err_len);
    if (have_r < 0) return -1;
    const cJSON *parts = cJSON_GetObjectItemCaseSensitive(req, "part");
    int part_count = 0;
    if (parts) {
        part_count = cJSON_GetArraySize(parts);
        if (!cJSON_IsArray(parts) || part_count < 1 || part_count > JC_MAX_PARTS) {
            snprintf(err, err_len, "'part' must be an array of 1 to %d part objects", JC_MAX_PARTS);
            return -1;
        }
        int i = 0;
        for (const cJSON *o = parts->child; o; o = o->next, ++i)
            if (parse_part(o, i, r, &s->body.parts[i], err, err_len)) return -1;
        s->body.part_count = part_count;
    }
    if (have_r) {
        jc_Part *disc = part_count == 0 ? find_part(&s->body, JC_PART_DISC) : NULL;
        if (disc && disc->radius_m == s->body.radius_m) disc->radius_m = r;
        s->body.radius_m = r;
    }
    static const struct { const char *name; jc_PartKind kind; int field; } shortcut[] = {
        {"disc-mass", JC_PART_DISC, 0}, {"rod-mass", JC_PART_ROD, 0},
        {"rod-offset", JC_PART_ROD, 1}, {"rod-radius", JC_PART_ROD, 2}};
    int shortcuts = 0;
    for (size_t k = 0; k < sizeof shortcut / sizeof shortcut[0]; ++k) {
        const int got = get_number(req, shortcut[k].name, &v, err, err_len);
        if (got < 0) return -1;
        if (!got) continue;
        ++shortcuts;
        jc_Part *p = find_part(&s->body, shortcut[k].kind);
        if (!p) {
            snprintf(err, err_len, "'%s' needs a body with a %s part (the paper or disc preset); with 'part', set it in the part",
                     shortcut[k].name, jc_part_kind_name(shortcut[k].kind));
            return -1;
        }
        *(shortcut[k].field == 0 ? &p->mass_kg : shortcut[k].field == 1 ? &p->offset_m : &p->radius_m) = v;
    }
    *body_changed = part_count > 0 || have_r || shortcuts > 0;
    return 0;
}

static int build_setup(const cJSON *req, jc_Setup *s, char *err, size_t err_len)
{
    char msg[256];
    const char *text = NULL;
    *s = jc_paper_setup();
    int got = get_string(req, "preset", &text, err, err_len);
    if (got < 0) return -1;
    if (got && jc_preset_setup(text, s, msg, sizeof msg) != JC_OK) {
        snprintf(err, err_len, "preset: %s", msg);
        return -1;
    }
    int body_changed = 0;
    if (build_body(req, s, &body_changed, err, err_len)) return -1;
    if (body_changed) s->paper_cm_offset_m = 0.0; /* the printed d was for the paper's body */
    for (size_t k = 0; k < sizeof scalars / sizeof scalars[0]; ++k) {
        double v;
        got = get_number(req, scalars[k].name, &v, err, err_len);
        if (got < 0) return -1;
        if (!got) continue;
        if (is_angle(scalars[k].name)) v *= WEB_PI / 180.0;
        memcpy((char *)s + scalars[k].field, &v, sizeof v);
        if (strcmp(scalars[k].name, "mu") == 0) s->mu_kinetic = v;
    }
    got = get_string(req, "impact-law", &text, err, err_len);
    if (got < 0) return -1;
    if (got && jc_impact_law_parse(text, &s->impact_law) != JC_OK) {
        snprintf(err, err_len, "impact-law: unknown law '%.40s' (allowed: stronge, poisson, newton)", text);
        return -1;
    }
    if (cJSON_HasObjectItem(req, "mu") && (cJSON_HasObjectItem(req, "mu-s") || cJSON_HasObjectItem(req, "mu-k"))) {
        snprintf(err, err_len, "'mu' sets both coefficients; give either 'mu' or 'mu-s'/'mu-k'");
        return -1;
    }
    if (jc_setup_validate(s, msg, sizeof msg) != JC_OK) {
        snprintf(err, err_len, "invalid setup: %s", msg);
        return -1;
    }
    return 0;
}

static int build_options(const cJSON *req, jc_SimOptions *o, char *err, size_t err_len)
{
    char msg[256];
    *o = jc_default_sim_options();
    o->max_samples = WEB_DEFAULT_MAX_SAMPLES;
    static const struct { const char *name; int integer; } keys[] = {
        {"t-max", 0}, {"sample-dt", 0}, {"rtol", 0}, {"atol", 0}, {"event-tol", 0}, {"contact-height", 0},
        {"max-events", 1}, {"max-samples", 1}};
    double *dst[] = {&o->t_max_s, &o->sample_dt_s, &o->ode_rtol, &o->ode_atol, &o->event_tol_s, &o->contact_height_m};
    for (size_t k = 0; k < sizeof keys / sizeof keys[0]; ++k) {
        double v;
        const int got = get_number(req, keys[k].name, &v, err, err_len);
        if (got < 0) return -1;
        if (!got) continue;
        if (!keys[k].integer) {
            *dst[k] = v;
            continue;
        }
        if (v != floor(v) || v < 1 || v > 1e7) {
            snprintf(err, err_len, "'%s' must be a whole number from 1 to 10000000", keys[k].name);
            return -1;
        }
        *(strcmp(keys[k].name, "max-events") == 0 ? &o->max_events : &o->max_samples) = (int)v;
    }
    if (jc_sim_options_validate(o, msg, sizeof msg) != JC_OK) {
        snprintf(err, err_len, "invalid simulation options: %s", msg);
        return -1;
    }
    return 0;
}

/* ---- the answer ---- */

static cJSON *setup_json(const jc_Model *m)
{
    const jc_Setup *s = &m->setup;
    cJSON *o = cJSON_CreateObject();
    cJSON *body = cJSON_AddObjectToObject(o, "body");
    cJSON_AddNumberToObject(body, "radius", m->body.radius_m);
    cJSON_AddNumberToObject(body, "mass", m->body.mass_kg);
    cJSON_AddNumberToObject(body, "cm_offset", m->body.cm_offset_m);
    cJSON_AddNumberToObject(body, "cm_angle", m->body.cm_angle_rad);
    cJSON_AddNumberToObject(body, "inertia_c", m->body.inertia_c_kgm2);
    cJSON_AddNumberToObject(body, "inertia_g", m->body.inertia_g_kgm2);
    cJSON *parts = cJSON_AddArrayToObject(body, "parts");
    for (int i = 0; i < s->body.part_count; ++i) {
        const jc_Part *p = &s->body.parts[i];
        cJSON *q = cJSON_CreateObject();
        cJSON_AddStringToObject(q, "kind", jc_part_kind_name(p->kind));
        cJSON_AddNumberToObject(q, "mass", p->mass_kg);
        cJSON_AddNumberToObject(q, "offset", p->offset_m);
        cJSON_AddNumberToObject(q, "angle", p->angle_rad);
        cJSON_AddNumberToObject(q, "radius", p->radius_m);
        cJSON_AddItemToArray(parts, q);
    }
    cJSON_AddNumberToObject(o, "incline", s->incline_rad);
    cJSON_AddNumberToObject(o, "g", s->gravity_mps2);
    cJSON_AddNumberToObject(o, "mu_s", s->mu_static);
    cJSON_AddNumberToObject(o, "mu_k", s->mu_kinetic);
    cJSON_AddNumberToObject(o, "restitution", s->restitution);
    cJSON_AddStringToObject(o, "impact_law", jc_impact_law_name(s->impact_law));
    cJSON_AddNumberToObject(o, "theta0", s->theta0_rad);
    cJSON_AddNumberToObject(o, "omega0", s->omega0_radps);
    cJSON_AddNumberToObject(o, "ramp_length", s->ramp_length_m);
    cJSON_AddNumberToObject(o, "theta_end", m->theta_end_rad);
    cJSON_AddNumberToObject(o, "paper_d", m->paper_d_m);
    cJSON_AddNumberToObject(o, "length", s->length_m);
    cJSON_AddNumberToObject(o, "air_density", s->air_density_kgpm3);
    cJSON_AddNumberToObject(o, "drag_coefficient", s->drag_coefficient);
    cJSON_AddNumberToObject(o, "lift_coefficient", s->lift_coefficient);
    cJSON_AddNumberToObject(o, "spin_drag", s->spin_drag_Nms2);
    cJSON_AddNumberToObject(o, "rolling_resistance", s->rolling_resistance_m);
    return o;
}

/* The names and fields of `jumpcyl simulate --json` (cli/outputs/report.c). */
static cJSON *event_json(const jc_Event *e)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "kind", jc_event_name(e->kind));
    cJSON_AddStringToObject(o, "mode_before", jc_mode_name(e->mode_before));
    cJSON_AddStringToObject(o, "mode_after", jc_mode_name(e->mode_after));
    cJSON_AddNumberToObject(o, "t", e->state.t_s);
    cJSON_AddNumberToObject(o, "x", e->state.x_m);
    cJSON_AddNumberToObject(o, "y", e->state.y_m);
    cJSON_AddNumberToObject(o, "theta", e->state.theta_rad);
    cJSON_AddNumberToObject(o, "omega", e->state.omega_radps);
    cJSON_AddNumberToObject(o, "vx", e->state.vx_mps);
    cJSON_AddNumberToObject(o, "vy", e->state.vy_mps);
    cJSON_AddNumberToObject(o, "slip", e->slip_mps);
    cJSON_AddNumberToObject(o, "normal", e->normal_N);
    cJSON_AddNumberToObject(o, "friction", e->friction_N);
    if (e->kind == JC_EVENT_LIFTOFF || (e->kind == JC_EVENT_BOUNCE && e->mode_after == JC_MODE_FLIGHT)) {
        cJSON_AddNumberToObject(o, "flight_time", e->flight_time_s);
        cJSON_AddNumberToObject(o, "hop_height", e->hop_height_m);
        if (isnan(e->landing_x_m)) cJSON_AddNullToObject(o, "landing_x");
        else cJSON_AddNumberToObject(o, "landing_x", e->landing_x_m);
    }
    if (e->kind == JC_EVENT_TOUCHDOWN || e->kind == JC_EVENT_BOUNCE) {
        cJSON_AddNumberToObject(o, "impact_speed", e->impact_speed_mps);
        cJSON_AddNumberToObject(o, "impulse_normal", e->impulse_normal_Ns);
        cJSON_AddNumberToObject(o, "impulse_tangent", e->impulse_tangent_Ns);
    }
    return o;
}

/* The samples as columns (one array per quantity), ready for plotting. */
enum { C_T, C_X, C_Y, C_VX, C_VY, C_THETA, C_OMEGA, C_CM_X, C_CM_Y, C_NORMAL, C_FRICTION, C_SLIP, C_GAP,
       C_KINETIC, C_POTENTIAL, C_FRICTION_LOSS, C_IMPACT_LOSS, C_AIR_LOSS, C_RR_LOSS, C_COUNT };

static double column_value(const jc_Sample *s, int c)
{
    switch (c) {
    case C_T: return s->state.t_s;
    case C_X: return s->state.x_m;
    case C_Y: return s->state.y_m;
    case C_VX: return s->state.vx_mps;
    case C_VY: return s->state.vy_mps;
    case C_THETA: return s->state.theta_rad;
    case C_OMEGA: return s->state.omega_radps;
    case C_CM_X: return s->cm_x_m;
    case C_CM_Y: return s->cm_y_m;
    case C_NORMAL: return s->normal_N;
    case C_FRICTION: return s->friction_N;
    case C_SLIP: return s->slip_mps;
    case C_GAP: return s->gap_m;
    case C_KINETIC: return s->kinetic_J;
    case C_POTENTIAL: return s->potential_J;
    case C_FRICTION_LOSS: return s->friction_loss_J;
    case C_IMPACT_LOSS: return s->impact_loss_J;
    case C_AIR_LOSS: return s->air_loss_J;
    default: return s->rolling_resistance_loss_J;
    }
}

/* A growing text, for the sample columns: printed straight, not through a
 * cJSON node per number. */
typedef struct {
    char *text;
    size_t len, cap;
    int failed;
} text_buf;

static void put(text_buf *b, const char *s, size_t n)
{
    if (b->failed) return;
    if (b->len + n + 1 > b->cap) {
        size_t cap = b->cap ? b->cap : 4096;
        while (cap < b->len + n + 1) cap *= 2;
        char *p = realloc(b->text, cap);
        if (!p) {
            b->failed = 1;
            return;
        }
        b->text = p;
        b->cap = cap;
    }
    memcpy(b->text + b->len, s, n);
    b->len += n;
    b->text[b->len] = '\0';
}

/* %.17g: always reads back to the same double, with one printf. cJSON's
 * way (%.15g, read back, %.17g if that differs) costs two or three calls,
 * and printf of a double is what dominates the answer's time in wasm
 * (musl): the samples printed this way take half the time. null for NaN
 * and infinities. */
static void put_number(text_buf *b, double v)
{
    char tmp[32];
    if (!isfinite(v)) {
        put(b, "null", 4);
        return;
    }
    const int n = snprintf(tmp, sizeof tmp, "%.17g", v);
    put(b, tmp, (size_t)n);
}

/* {"count": N, "mode": [...], "t": [...], ...} as raw JSON. */
static cJSON *samples_json(const jc_Run *run)
{
    static const char *const names[C_COUNT] = {
        "t", "x", "y", "vx", "vy", "theta", "omega", "cm_x", "cm_y", "normal", "friction", "slip", "gap",
        "kinetic", "potential", "friction_loss", "impact_loss", "air_loss", "rolling_resistance_loss"};
    text_buf b = {NULL, 0, 0, 0};
    char head[64];
    put(&b, head, (size_t)snprintf(head, sizeof head, "{\"count\":%d,\"mode\":[", run->sample_count));
    for (int i = 0; i < run->sample_count; ++i) {
        const char *m = jc_mode_name(run->samples[i].mode);
        if (i) put(&b, ",", 1);
        put(&b, "\"", 1);
        put(&b, m, strlen(m));
        put(&b, "\"", 1);
    }
    put(&b, "]", 1);
    for (int c = 0; c < C_COUNT; ++c) {
        put(&b, ",\"", 2);
        put(&b, names[c], strlen(names[c]));
        put(&b, "\":[", 3);
        for (int i = 0; i < run->sample_count; ++i) {
            if (i) put(&b, ",", 1);
            put_number(&b, column_value(&run->samples[i], c));
        }
        put(&b, "]", 1);
    }
    put(&b, "}", 1);
    cJSON *raw = b.failed ? NULL : cJSON_CreateRaw(b.text);
    free(b.text);
    return raw;
}

static cJSON *energy_json(const jc_EnergyReport *e)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "kinetic", e->kinetic_J);
    cJSON_AddNumberToObject(o, "potential", e->potential_J);
    cJSON_AddNumberToObject(o, "friction_loss", e->friction_loss_J);
    cJSON_AddNumberToObject(o, "impact_loss", e->impact_loss_J);
    cJSON_AddNumberToObject(o, "air_loss", e->air_loss_J);
    cJSON_AddNumberToObject(o, "rolling_resistance_loss", e->rolling_resistance_loss_J);
    cJSON_AddNumberToObject(o, "balance_error", e->balance_error_J);
    return o;
}

static void add_state(cJSON *o, const jc_State *st)
{
    cJSON_AddNumberToObject(o, "t", st->t_s);
    cJSON_AddNumberToObject(o, "x", st->x_m);
    cJSON_AddNumberToObject(o, "y", st->y_m);
    cJSON_AddNumberToObject(o, "theta", st->theta_rad);
    cJSON_AddNumberToObject(o, "omega", st->omega_radps);
    cJSON_AddNumberToObject(o, "vx", st->vx_mps);
    cJSON_AddNumberToObject(o, "vy", st->vy_mps);
}

static cJSON *run_json(const jc_Model *m, const jc_Run *run)
{
    jc_RunSummary sum;
    jc_run_summarize(run, &sum);
    cJSON *doc = cJSON_CreateObject();
    if (!doc) return NULL;
    cJSON_AddTrueToObject(doc, "ok");
    cJSON_AddStringToObject(doc, "version", jc_version());
    cJSON_AddItemToObject(doc, "setup", setup_json(m));
    cJSON *ev = cJSON_AddArrayToObject(doc, "events");
    for (int i = 0; ev && i < run->event_count; ++i) cJSON_AddItemToArray(ev, event_json(&run->events[i]));
    cJSON *samples = samples_json(run);
    if (!samples) {
        cJSON_Delete(doc);
        return NULL;
    }
    cJSON_AddItemToObject(doc, "samples", samples);
    cJSON_AddStringToObject(doc, "termination", jc_termination_name(run->termination));
    cJSON_AddStringToObject(doc, "termination_detail", run->termination_detail);
    cJSON_AddNumberToObject(doc, "t_end", run->final_state.t_s);
    cJSON_AddStringToObject(doc, "final_mode", jc_mode_name(run->final_mode));
    cJSON_AddItemToObject(doc, "energy", energy_json(&run->energy));
    cJSON_AddNumberToObject(doc, "energy_gaining_impacts", run->energy_gaining_impacts);
    cJSON_AddNumberToObject(doc, "largest_impact_gain_J", run->largest_impact_gain_J);
    cJSON_AddNumberToObject(doc, "micro_slips", (double)run->micro_slips);
    cJSON_AddNumberToObject(doc, "rocking_period_s", run->rocking_period_s);
    cJSON_AddNumberToObject(doc, "ode_steps", (double)run->ode_steps);
    if (sum.first_liftoff >= 0) {
        cJSON *fl = cJSON_AddObjectToObject(doc, "first_liftoff");
        cJSON_AddNumberToObject(fl, "event", sum.first_liftoff);
        add_state(fl, &sum.first_liftoff_state);
    } else {
        cJSON_AddNullToObject(doc, "first_liftoff");
    }
    cJSON *s = cJSON_AddObjectToObject(doc, "summary");
    cJSON_AddNumberToObject(s, "liftoffs", sum.liftoffs);
    cJSON_AddNumberToObject(s, "bounces", sum.bounces);
    cJSON_AddNumberToObject(s, "largest_hop", sum.largest_hop_m);
    cJSON_AddNumberToObject(s, "flight_time", sum.flight_time_s);
    cJSON_AddNumberToObject(s, "first_slip", sum.first_slip);
    return doc;
}

/* {"ok": false, "error": "..."}: the message on one line. */
static char *error_text(const char *msg)
{
    char line[ERR_LEN];
    snprintf(line, sizeof line, "%s", msg);
    for (char *c = line; *c; ++c)
        if (*c == '\n' || *c == '\r') *c = ' ';
    cJSON *doc = cJSON_CreateObject();
    cJSON_AddFalseToObject(doc, "ok");
    cJSON_AddStringToObject(doc, "error", line);
    char *text = doc ? cJSON_PrintUnformatted(doc) : NULL;
    cJSON_Delete(doc);
    return text;
}

static char *print_or_fail(cJSON *doc)
{
    char *text = doc ? cJSON_PrintUnformatted(doc) : NULL;
    cJSON_Delete(doc);
    return text ? text : error_text("out of memory for the answer");
}

/* ---- exported ---- */

JC_WEB_EXPORT char *jc_web_simulate(const char *request_json)
{
    char err[ERR_LEN];
    gsl_set_error_handler_off(); /* GSL reports failures as status codes, never aborts */
    cJSON *req = request_json ? cJSON_Parse(request_json) : NULL;
    if (!cJSON_IsObject(req)) {
        cJSON_Delete(req);
        return error_text("the request is not a JSON object (e.g. {\"incline\": 30})");
    }
    jc_Setup setup;
    jc_SimOptions options;
    if (check_keys(req, err, sizeof err) || build_setup(req, &setup, err, sizeof err) ||
        build_options(req, &options, err, sizeof err)) {
        cJSON_Delete(req);
        return error_text(err);
    }
    cJSON_Delete(req);

    jc_Model *model = malloc(sizeof *model);
    if (!model) return NULL;
    if (jc_model_init(model, &setup, err, sizeof err) != JC_OK) {
        free(model);
        return error_text(err);
    }
    jc_Run run = {0};
    const int st = jc_simulate(model, &options, &run, err, sizeof err);
    char *text;
    if (st != JC_OK) {
        char msg[ERR_LEN + 40];
        snprintf(msg, sizeof msg, "simulation failed (%s): %s", jc_status_text(st), err);
        text = error_text(msg);
    } else {
        text = print_or_fail(run_json(model, &run));
    }
    jc_run_free(&run);
    free(model);
    return text;
}

JC_WEB_EXPORT char *jc_web_presets(void)
{
    cJSON *arr = cJSON_CreateArray();
    for (int i = 0; arr && jc_preset_name(i); ++i) {
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "name", jc_preset_name(i));
        cJSON_AddStringToObject(o, "description", jc_preset_description(i));
        cJSON_AddItemToArray(arr, o);
    }
    return print_or_fail(arr);
}

JC_WEB_EXPORT const char *jc_web_version(void)
{
    return jc_version();
}

JC_WEB_EXPORT void jc_web_free(char *text)
{
    free(text);
}
