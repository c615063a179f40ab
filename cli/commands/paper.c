/* jumpcyl paper: the seed paper's Table 1 recomputed beside the exact rolling
 * model and the measurement. Only the printed and measured values are data
 * (jc_paper_table); every other number comes from the library. */
#include "commands.h"
#include "inputs.h"
#include "batch.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <string.h>

#define ROWS_MAX 8

/* Friction values of the sweep line: how the first lift-off moves with mu. */
static const double sweep_mu[] = {0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0};
#define SWEEP_COUNT ((int)(sizeof sweep_mu / sizeof sweep_mu[0]))

/* Drag coefficient of the drag column: a short cylinder in cross-flow
 * (length/diameter 0.28, Re about 4e4); docs/physics.md gives the source
 * and how the result moves with C_d. */
#define PAPER_DRAG_CD 0.6

typedef struct {
    int found;
    double theta_rad, x_m;
    double first_hop_m;  /* largest gap of the first flight */
    jc_RunSummary summary;
    jc_Termination termination;
    int energy_gaining_impacts;
    double later_hop_m;  /* largest gap of the flights after the first landing */
} full_result;

typedef struct {
    jc_PaperTableRow table;
    jc_Model model;
    jc_PaperResult paper;
    jc_RollingResult rolling;
    int nearest;  /* index of the intersection nearest the printed angle */
    full_result full;
    full_result drag; /* the full model with air drag at PAPER_DRAG_CD */
    full_result newton; /* the full model with Newton's impact law instead of Stronge's */
    full_result sweep[SWEEP_COUNT];
    jc_Stats mc;        /* the full model's first lift-off under the inputs' uncertainties */
    jc_Tally mc_counts;
} paper_row;

static void help(void)
{
    puts("Usage: jumpcyl paper [SETUP OPTIONS] [--json FILE]\n"
         "The seed paper's Table 1 (inclines 15, 30, 45 deg) side by side: the printed values,\n"
         "the paper's Eq. 9 recomputed (first intersection and later ones), the exact rolling\n"
         "model (slip onset and the N = 0 diagnostic), the full model (first lift-off, hops,\n"
         "largest hop, and how the lift-off moves with friction from 0.3 to 1.0), the full\n"
         "model with air drag (C_d 0.6), and the measurement with its error bar.\n"
         "Setup options change the paper's setup for every row; the incline is the table's, and\n"
         "the body stays the paper's cylinder, the only one it measured (for another body:\n"
         "jumpcyl predict).\n"
         "\n"
         "  --json FILE machine-readable output into FILE (- or no FILE: standard output, in\n"
         "              place of the table): rows[], each with incline_deg, printed,\n"
         "              paper_model, rolling, full, drag, measured; angles theta in rad,\n"
         "              positions x in m\n"
         "  -h, --help  this help\n");
}

/* Printed values carry two decimals: differences within half a unit of the
 * last printed digit are rounding, not disagreement. */
#define PRINTED_HALF_UNIT_RAD 0.005

static int nearest_root(const jc_PaperResult *p, double theta)
{
    int best = -1;
    for (int i = 0; i < p->root_count; ++i)
        if (best < 0 || fabs(p->theta_rad[i] - theta) < fabs(p->theta_rad[best] - theta)) best = i;
    return best;
}

static int inside(double x, const jc_PaperTableRow *t)
{
    return fabs(x - t->measured_x_m) <= t->measured_error_m;
}

/* The full model's first lift-off and hops for a setup. Runs are where the
 * time goes (27 of them): a stop request is honoured between them. A
 * library status, JC_ESTOPPED after a stop signal. */
static int run_full(const jc_Setup *s, full_result *out, char *err, size_t err_len)
{
    if (cli_stop_requested()) return JC_ESTOPPED;
    *out = (full_result){0};
    jc_Model m;
    int st = jc_model_init(&m, s, err, err_len);
    if (st != JC_OK) return st;
    const jc_SimOptions o = jc_default_sim_options();
    jc_Run run;
    st = jc_simulate(&m, &o, &run, err, err_len);
    if (st == JC_OK) {
        jc_run_summarize(&run, &out->summary);
        out->termination = run.termination;
        out->energy_gaining_impacts = run.energy_gaining_impacts;
        out->found = out->summary.first_liftoff >= 0;
        if (out->found) {
            const jc_Event *e = &run.events[out->summary.first_liftoff];
            out->theta_rad = e->state.theta_rad;
            out->x_m = e->state.x_m;
            out->first_hop_m = e->hop_height_m;
            for (int i = out->summary.first_liftoff + 1; i < run.event_count; ++i) {
                const jc_Event *f = &run.events[i];
                if (f->kind == JC_EVENT_LIFTOFF || (f->kind == JC_EVENT_BOUNCE && f->mode_after == JC_MODE_FLIGHT))
                    out->later_hop_m = fmax(out->later_hop_m, f->hop_height_m);
            }
        }
    }
    jc_run_free(&run);
    return st;
}

/* The Monte Carlo spread of the full model's first lift-off at the row's
 * incline: the paper's tolerances and the unmeasured friction and
 * restitution (jc_study_default_spreads, cli/batch/mc_job.c). */
static int run_uncertainty(const cli_SetupArgs *sa, paper_row *r, char *err, size_t err_len)
{
    const int st = cli_mc_liftoff_stats("paper", sa, r->table.incline_deg, CLI_PAPER_MC_SAMPLES, CLI_PAPER_MC_SEED,
                                        &r->mc, &r->mc_counts);
    if (st == EXIT_OK) return JC_OK;
    if (cli_stop_requested()) return JC_ESTOPPED;
    snprintf(err, err_len, "the Monte Carlo runs failed");
    return JC_ENUMERIC;
}

/* The table's rows; *count of them are complete. A library status:
 * JC_ESTOPPED when a stop signal came (the row under way is dropped). */
static int compute_rows(const jc_Setup *base, const cli_SetupArgs *sa, paper_row *rows, int *count, char *err,
                        size_t err_len)
{
    const jc_PaperTableRow *table;
    int n = jc_paper_table(&table);
    if (n > ROWS_MAX) n = ROWS_MAX;
    for (int i = 0; i < n; ++i) {
        *count = i;
        if (cli_stop_requested()) return JC_ESTOPPED;
        jc_Setup s = *base;
        s.incline_rad = table[i].incline_deg * CLI_PI / 180.0;
        paper_row *r = &rows[i];
        r->table = table[i];
        int st;
        if ((st = jc_model_init(&r->model, &s, err, err_len)) != JC_OK ||
            (st = jc_paper_solve(&r->model, &r->paper, err, err_len)) != JC_OK ||
            (st = jc_rolling_predict(&r->model, &r->rolling, err, err_len)) != JC_OK)
            return st;
        r->nearest = nearest_root(&r->paper, table[i].printed_theta_rad);
        if ((st = run_full(&s, &r->full, err, err_len)) != JC_OK) return st;
        jc_Setup with_drag = s;
        with_drag.drag_coefficient = PAPER_DRAG_CD;
        if ((st = run_full(&with_drag, &r->drag, err, err_len)) != JC_OK) return st;
        jc_Setup newton = s;
        newton.impact_law = JC_IMPACT_NEWTON;
        if ((st = run_full(&newton, &r->newton, err, err_len)) != JC_OK) return st;
        for (int k = 0; k < SWEEP_COUNT; ++k) {
            jc_Setup sw = s;
            sw.mu_static = sw.mu_kinetic = sweep_mu[k];
            if ((st = run_full(&sw, &r->sweep[k], err, err_len)) != JC_OK) return st;
        }
        if ((st = run_uncertainty(sa, r, err, err_len)) != JC_OK) return st;
    }
    *count = n;
    return JC_OK;
}

/* ---- text ---- */

/* One cell of a row: the value, or a placeholder where that run has none. */
static void cell(int have, const char *fmt, double v, const char *none)
{
    if (have) printf(fmt, v);
    else printf(" %14s", none);
}

static void cell_x(const jc_RollingCrossing *c)
{
    cell(c->found, " %14.2f", c->state.x_m * 100, "none");
}

static void print_flags(const paper_row *rows, int n)
{
    printf("\nWhere the recomputed paper's model differs from the printed table (beyond rounding):\n");
    int any = 0;
    for (int i = 0; i < n; ++i) {
        const paper_row *r = &rows[i];
        const jc_PaperResult *p = &r->paper;
        const double printed = r->table.printed_theta_rad;
        if (p->first < 0) {
            printf("  * %2.0f deg: no intersection at all, printed %.2f rad\n", r->table.incline_deg, printed);
            any = 1;
            continue;
        }
        const double diff = p->theta_rad[p->first] - printed;
        if (fabs(diff) <= PRINTED_HALF_UNIT_RAD) continue;
        any = 1;
        printf("  * %2.0f deg: first intersection %.4f rad (%.2f cm), printed %.2f rad (%.1f cm): "
               "%+.4f rad, %+.2f cm (%+.1f%%)\n",
               r->table.incline_deg, p->theta_rad[p->first], p->x_m[p->first] * 100, printed,
               r->table.printed_x_m * 100, diff, diff * r->model.body.radius_m * 100, 100 * diff / printed);
        if (r->nearest != p->first && r->nearest >= 0)
            printf("           the printed angle is intersection #%d (%.4f rad, %+.4f rad off); the earlier\n"
                   "           window %.4f..%.4f rad, where th'^2/g exceeds cos(a)/(d cos th), was missed\n",
                   r->nearest + 1, p->theta_rad[r->nearest], p->theta_rad[r->nearest] - printed,
                   p->theta_rad[p->first], p->root_count > 1 ? p->theta_rad[p->first + 1] : NAN);
    }
    if (!any) printf("  none\n");
}

static void print_full(const paper_row *rows, int n)
{
    const jc_Setup *s0 = &rows[0].model.setup;
    printf("\n\nFull model: roll, slip, fly, land (mu_s = %.2f, mu_k = %.2f, e = %.2f; impacts by Stronge's law:\n"
           "Darboux-Keller in the normal impulse with energetic restitution, docs/physics.md section 4)\n",
           s0->mu_static, s0->mu_kinetic, s0->restitution);
    printf("%-40s", "  first lift-off angle (rad)");
    for (int i = 0; i < n; ++i) cell(rows[i].full.found, " %14.4f", rows[i].full.theta_rad, "none");
    printf("\n%-40s", "  first lift-off position (cm)");
    for (int i = 0; i < n; ++i) cell(rows[i].full.found, " %14.2f", rows[i].full.x_m * 100, "none");
    printf("\n%-40s", "  minus measured (cm)");
    for (int i = 0; i < n; ++i)
        cell(rows[i].full.found, " %+14.2f", (rows[i].full.x_m - rows[i].table.measured_x_m) * 100, "-");
    printf("\n%-40s", "  inside the error bar");
    for (int i = 0; i < n; ++i)
        printf(" %14s", !rows[i].full.found ? "-" : inside(rows[i].full.x_m, &rows[i].table) ? "yes" : "no");
    printf("\n%-40s", "  hops on the ramp (lift-offs)");
    for (int i = 0; i < n; ++i) printf(" %14d", rows[i].full.summary.liftoffs);
    printf("\n%-40s", "  bounces (impacts back into flight)");
    for (int i = 0; i < n; ++i) printf(" %14d", rows[i].full.summary.bounces);
    printf("\n%-40s", "  largest hop, gap under the rim (mm)");
    for (int i = 0; i < n; ++i) printf(" %14.2f", rows[i].full.summary.largest_hop_m * 1e3);
    printf("\nAfter the first lift-off: Stronge's law against Newton's (v_n after = -e v_n before);\n"
           "a later hop is a flight after the first landing, the first flight is the same under both\n");
    printf("%-40s", "  hops / bounces, Stronge");
    for (int i = 0; i < n; ++i) printf(" %9d / %2d", rows[i].full.summary.liftoffs, rows[i].full.summary.bounces);
    printf("\n%-40s", "  hops / bounces, Newton");
    for (int i = 0; i < n; ++i) printf(" %9d / %2d", rows[i].newton.summary.liftoffs, rows[i].newton.summary.bounces);
    printf("\n%-40s", "  largest later hop (mm), Stronge");
    for (int i = 0; i < n; ++i) printf(" %14.2f", rows[i].full.later_hop_m * 1e3);
    printf("\n%-40s", "  largest later hop (mm), Newton");
    for (int i = 0; i < n; ++i) printf(" %14.2f", rows[i].newton.later_hop_m * 1e3);
    printf("\n%-40s", "  later hop, Newton against Stronge");
    for (int i = 0; i < n; ++i) {
        const double a = rows[i].full.later_hop_m, b = rows[i].newton.later_hop_m;
        /* Rounded to the printed 0.1 % first, so that a tiny negative is not "-0.0". */
        if (a > 0.0) printf(" %+13.1f%%", round(1000.0 * (b - a) / a) / 10.0 + 0.0);
        else printf(" %14s", "-");
    }
    printf("\n%-40s", "  impacts that gained energy, Newton");
    for (int i = 0; i < n; ++i) printf(" %14d", rows[i].newton.energy_gaining_impacts);
    printf("\nFull model with air drag, C_d = %.2f (rho = %.3f kg/m3, A = 2 r L = %.0f cm2; docs/physics.md)\n",
           PAPER_DRAG_CD, s0->air_density_kgpm3, 2e4 * rows[0].model.body.radius_m * s0->length_m);
    printf("%-40s", "  first lift-off position (cm)");
    for (int i = 0; i < n; ++i) cell(rows[i].drag.found, " %14.2f", rows[i].drag.x_m * 100, "none");
    printf("\n%-40s", "  moved by drag (cm)");
    for (int i = 0; i < n; ++i)
        cell(rows[i].drag.found && rows[i].full.found, " %+14.2f", (rows[i].drag.x_m - rows[i].full.x_m) * 100, "-");
    printf("\n%-40s", "  toward the measurement");
    for (int i = 0; i < n; ++i) {
        const paper_row *r = &rows[i];
        if (!r->drag.found || !r->full.found) { printf(" %14s", "-"); continue; }
        const double before = fabs(r->full.x_m - r->table.measured_x_m), after = fabs(r->drag.x_m - r->table.measured_x_m);
        printf(" %14s", after < before ? "yes" : "no");
    }
    printf("\n%-40s", "  inside the error bar");
    for (int i = 0; i < n; ++i)
        printf(" %14s", !rows[i].drag.found ? "-" : inside(rows[i].drag.x_m, &rows[i].table) ? "yes" : "no");
    printf("\n%-40s", "  first hop (mm): without -> with drag");
    for (int i = 0; i < n; ++i) printf("   %5.1f -> %4.1f", rows[i].full.first_hop_m * 1e3, rows[i].drag.first_hop_m * 1e3);
    printf("\nFirst lift-off position (cm) against friction mu_s = mu_k:\n");
    for (int k = 0; k < SWEEP_COUNT; ++k) {
        char label[48];
        snprintf(label, sizeof label, "  mu = %.1f", sweep_mu[k]);
        printf("%-40s", label);
        for (int i = 0; i < n; ++i) {
            const full_result *f = &rows[i].sweep[k];
            if (f->found) printf(" %11.2f %-2s", f->x_m * 100, inside(f->x_m, &rows[i].table) ? "in" : "");
            else printf(" %14s", "none");
        }
        printf("\n");
    }
    printf("  ('in': inside the measured error bar)");
}

static int mc_inside(const paper_row *r)
{
    return r->mc.n > 0 && r->table.measured_x_m >= r->mc.p2_5 && r->table.measured_x_m <= r->mc.p97_5;
}

static void print_uncertainty(const paper_row *rows, int n)
{
    printf("\nUncertainty of the full model (Monte Carlo, %d samples per incline, seed %d: the paper's\n"
           "tolerances as normal spreads: r, rod offset 0.05 cm, masses 0.05 g, theta0 3 deg; friction\n"
           "0.3..1.0 and restitution 0.1..0.6 uniform, as the paper did not measure them; 'jumpcyl mc')\n",
           CLI_PAPER_MC_SAMPLES, CLI_PAPER_MC_SEED);
    printf("%-40s", "  first lift-off, median (cm)");
    for (int i = 0; i < n; ++i) cell(rows[i].mc.n > 0, " %14.2f", rows[i].mc.p50 * 100, "none");
    printf("\n%-40s", "  95 % interval (cm)");
    for (int i = 0; i < n; ++i) {
        if (rows[i].mc.n > 0) printf(" %6.1f..%6.1f", rows[i].mc.p2_5 * 100, rows[i].mc.p97_5 * 100);
        else printf(" %14s", "none");
    }
    printf("\n%-40s", "  samples that lift off on the ramp");
    for (int i = 0; i < n; ++i) {
        const jc_Tally *t = &rows[i].mc_counts;
        printf(" %13.1f%%", t->valid ? 100.0 * (double)t->liftoffs / (double)t->valid : 0.0);
    }
    printf("\n%-40s", "  measurement inside the 95 % interval");
    for (int i = 0; i < n; ++i) printf(" %14s", rows[i].mc.n == 0 ? "-" : mc_inside(&rows[i]) ? "yes" : "no");
    printf("\n%-40s", "  interval and error bar overlap");
    for (int i = 0; i < n; ++i) {
        const paper_row *r = &rows[i];
        const int overlap = r->mc.n > 0 && r->mc.p97_5 >= r->table.measured_x_m - r->table.measured_error_m &&
                            r->mc.p2_5 <= r->table.measured_x_m + r->table.measured_error_m;
        printf(" %14s", r->mc.n == 0 ? "-" : overlap ? "yes" : "no");
    }
}

static void print_text(const paper_row *rows, int n)
{
    const jc_Model *m0 = &rows[0].model;
    printf("The seed paper's Table 1 recomputed (Gomez, Hernandez-Gomez, Marquina,\n"
           "\"A Jumping Cylinder on an Incline\"). Positions are the centre's travel along the incline.\n\n");
    cli_print_setup(stdout, m0, 0);
    printf("\n%-40s", "");
    for (int i = 0; i < n; ++i) printf(" %11.0f deg", rows[i].table.incline_deg);
    printf("\nPrinted (Table 1)\n%-40s", "  jump angle (rad)");
    for (int i = 0; i < n; ++i) printf(" %14.2f", rows[i].table.printed_theta_rad);
    printf("\n%-40s", "  jump position (cm)");
    for (int i = 0; i < n; ++i) printf(" %14.1f", rows[i].table.printed_x_m * 100);
    printf("\nPaper's Eq. 9 recomputed (d = %.3f cm)\n%-40s", rows[0].paper.cm_offset_m * 100,
           "  first intersection (rad)");
    for (int i = 0; i < n; ++i) {
        const jc_PaperResult *p = &rows[i].paper;
        if (p->first >= 0) printf(" %14.4f", p->theta_rad[p->first]);
        else printf(" %14s", "none");
    }
    printf("\n%-40s", "  jump position (cm)");
    for (int i = 0; i < n; ++i) {
        const jc_PaperResult *p = &rows[i].paper;
        if (p->first >= 0) printf(" %14.2f", p->x_m[p->first] * 100);
        else printf(" %14s", "none");
    }
    printf("\n%-40s", "  minus printed (cm)");
    for (int i = 0; i < n; ++i) {
        const jc_PaperResult *p = &rows[i].paper;
        if (p->first >= 0) printf(" %+14.2f", (p->x_m[p->first] - rows[i].table.printed_x_m) * 100);
        else printf(" %14s", "-");
    }
    printf("\n%-40s", "  intersection nearest the printed (rad)");
    for (int i = 0; i < n; ++i) {
        const paper_row *r = &rows[i];
        if (r->nearest >= 0) printf("   #%d %9.4f", r->nearest + 1, r->paper.theta_rad[r->nearest]);
        else printf(" %14s", "none");
    }
    printf("\nExact rolling model (d = %.3f cm)\n", m0->body.cm_offset_m * 100);
    char label[64];
    snprintf(label, sizeof label, "  slip onset, mu_s = %.2f (cm)", m0->setup.mu_static);
    printf("%-40s", label);
    for (int i = 0; i < n; ++i) cell_x(&rows[i].rolling.slip);
    printf("\n%-40s", "  N = 0, diagnostic only (cm)");
    for (int i = 0; i < n; ++i) cell_x(&rows[i].rolling.liftoff);
    printf("\n%-40s", "Measured jump position (cm)");
    for (int i = 0; i < n; ++i)
        printf("   %6.1f +- %3.1f", rows[i].table.measured_x_m * 100, rows[i].table.measured_error_m * 100);
    printf("\n%-40s", "  printed position inside the error bar");
    for (int i = 0; i < n; ++i) printf(" %14s", inside(rows[i].table.printed_x_m, &rows[i].table) ? "yes" : "no");
    printf("\n%-40s", "  paper's model inside the error bar");
    for (int i = 0; i < n; ++i) {
        const jc_PaperResult *p = &rows[i].paper;
        printf(" %14s", p->first < 0 ? "-" : inside(p->x_m[p->first], &rows[i].table) ? "yes" : "no");
    }
    printf("\n%-40s", "  rolling N = 0 inside the error bar");
    for (int i = 0; i < n; ++i) {
        const jc_RollingCrossing *c = &rows[i].rolling.liftoff;
        printf(" %14s", !c->found ? "-" : inside(c->state.x_m, &rows[i].table) ? "yes" : "no");
    }
    print_full(rows, n);
    print_uncertainty(rows, n);
    printf("\n\nAll intersections of Eq. 9 up to the ramp end (rad); the first is the paper's prediction:\n");
    for (int i = 0; i < n; ++i) {
        printf("  %2.0f deg:", rows[i].table.incline_deg);
        for (int k = 0; k < rows[i].paper.root_count; ++k) printf(" %.4f", rows[i].paper.theta_rad[k]);
        printf("\n");
    }
    print_flags(rows, n);
    printf("\nNotes:\n"
           "  * The paper's model uses d = %.4f cm (%s) and I_CM = M1 r^2/2 + M d^2; the exact\n"
           "    model uses d = %.4f cm from the parts and I_C with every part's own inertia.\n"
           "  * The rolling N = 0 point is a diagnostic, not the physical jump: there F != 0, so with\n"
           "    finite friction the cylinder slips first; the slip onset row is where rolling ends.\n"
           "    The full model follows the motion through slip, re-stick, lift-off and landing.\n"
           "  * Friction: the paper gives none; mu = %.2f is a nominal value, not a measurement.\n"
           "    The sweep shows how far the first lift-off moves with it (docs/physics.md).\n",
           rows[0].paper.cm_offset_m * 100,
           m0->setup.paper_cm_offset_m > 0.0 ? "as printed, rounded" : "the exact value",
           m0->body.cm_offset_m * 100, m0->setup.mu_static);
    if (m0->setup.theta0_rad != 0.0 || m0->setup.omega0_radps != 0.0)
        printf("  * The paper's model ignores theta0 = %.4g deg and omega0 = %.4g rad/s: it starts at rest\n"
               "    at th = 0. The exact rolling model and the full model start from them.\n",
               cli_deg(m0->setup.theta0_rad), m0->setup.omega0_radps);
}

/* ---- JSON ---- */

static cJSON *theta_x(double theta, double x)
{
    cJSON *o = cJSON_CreateObject();
    if (!isnan(theta)) cJSON_AddNumberToObject(o, "theta", theta);
    cJSON_AddNumberToObject(o, "x", x);
    return o;
}

static cJSON *json_row(const paper_row *r)
{
    const jc_PaperResult *p = &r->paper;
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "incline_deg", r->table.incline_deg);
    cJSON_AddItemToObject(o, "printed", theta_x(r->table.printed_theta_rad, r->table.printed_x_m));
    cJSON *pm = p->first >= 0 ? theta_x(p->theta_rad[p->first], p->x_m[p->first]) : cJSON_CreateObject();
    if (p->first < 0) {
        cJSON_AddNullToObject(pm, "theta");
        cJSON_AddNullToObject(pm, "x");
    }
    cJSON_AddItemToObject(pm, "roots", cJSON_CreateDoubleArray(p->theta_rad, p->root_count));
    cJSON_AddNumberToObject(pm, "cm_offset", p->cm_offset_m);
    cJSON_AddNumberToObject(pm, "nearest_printed_index", r->nearest);
    if (p->first >= 0)
        cJSON_AddNumberToObject(pm, "minus_printed_theta", p->theta_rad[p->first] - r->table.printed_theta_rad);
    cJSON_AddItemToObject(o, "paper_model", pm);
    cJSON *ro = cJSON_CreateObject();
    const jc_RollingCrossing *lo = &r->rolling.liftoff;
    if (lo->found) {
        cJSON_AddNumberToObject(ro, "theta", lo->state.theta_rad);
        cJSON_AddNumberToObject(ro, "x", lo->state.x_m);
    } else {
        cJSON_AddNullToObject(ro, "theta");
        cJSON_AddNullToObject(ro, "x");
    }
    cJSON_AddStringToObject(ro, "note", "rolling N = 0: a diagnostic, not the physical jump");
    cJSON_AddItemToObject(ro, "liftoff", cli_json_crossing(lo));
    cJSON_AddItemToObject(ro, "slip", cli_json_crossing(&r->rolling.slip));
    cJSON_AddNumberToObject(ro, "mu_s", r->model.setup.mu_static);
    cJSON_AddItemToObject(o, "rolling", ro);
    cJSON *fu = r->full.found ? theta_x(r->full.theta_rad, r->full.x_m) : cJSON_CreateObject();
    if (!r->full.found) {
        cJSON_AddNullToObject(fu, "theta");
        cJSON_AddNullToObject(fu, "x");
    }
    cJSON_AddNumberToObject(fu, "hops", r->full.summary.liftoffs);
    cJSON_AddNumberToObject(fu, "bounces", r->full.summary.bounces);
    cJSON_AddNumberToObject(fu, "largest_hop", r->full.summary.largest_hop_m);
    cJSON_AddNumberToObject(fu, "first_hop", r->full.first_hop_m);
    cJSON_AddBoolToObject(fu, "inside_error_bar", r->full.found && inside(r->full.x_m, &r->table));
    cJSON_AddNumberToObject(fu, "mu_s", r->model.setup.mu_static);
    cJSON_AddNumberToObject(fu, "mu_k", r->model.setup.mu_kinetic);
    cJSON_AddNumberToObject(fu, "restitution", r->model.setup.restitution);
    cJSON_AddStringToObject(fu, "impact_law", jc_impact_law_name(r->model.setup.impact_law));
    cJSON *nw = cJSON_AddObjectToObject(fu, "newton");
    cJSON_AddNumberToObject(nw, "hops", r->newton.summary.liftoffs);
    cJSON_AddNumberToObject(nw, "bounces", r->newton.summary.bounces);
    cJSON_AddNumberToObject(nw, "largest_hop", r->newton.summary.largest_hop_m);
    cJSON_AddNumberToObject(nw, "largest_later_hop", r->newton.later_hop_m);
    cJSON_AddNumberToObject(fu, "largest_later_hop", r->full.later_hop_m);
    cJSON_AddNumberToObject(nw, "energy_gaining_impacts", r->newton.energy_gaining_impacts);
    cJSON *sw = cJSON_AddArrayToObject(fu, "friction_sweep");
    for (int k = 0; k < SWEEP_COUNT; ++k) {
        cJSON *point = cJSON_CreateObject();
        cJSON_AddNumberToObject(point, "mu", sweep_mu[k]);
        if (r->sweep[k].found) cJSON_AddNumberToObject(point, "x", r->sweep[k].x_m);
        else cJSON_AddNullToObject(point, "x");
        cJSON_AddItemToArray(sw, point);
    }
    cJSON_AddItemToObject(o, "full", fu);
    cJSON *dr = r->drag.found ? theta_x(r->drag.theta_rad, r->drag.x_m) : cJSON_CreateObject();
    if (!r->drag.found) {
        cJSON_AddNullToObject(dr, "theta");
        cJSON_AddNullToObject(dr, "x");
    }
    cJSON_AddNumberToObject(dr, "drag_coefficient", PAPER_DRAG_CD);
    cJSON_AddNumberToObject(dr, "hops", r->drag.summary.liftoffs);
    cJSON_AddNumberToObject(dr, "first_hop", r->drag.first_hop_m);
    cJSON_AddBoolToObject(dr, "inside_error_bar", r->drag.found && inside(r->drag.x_m, &r->table));
    if (r->drag.found && r->full.found) {
        cJSON_AddNumberToObject(dr, "moved_by_drag", r->drag.x_m - r->full.x_m);
        cJSON_AddBoolToObject(dr, "toward_measurement",
                              fabs(r->drag.x_m - r->table.measured_x_m) < fabs(r->full.x_m - r->table.measured_x_m));
    }
    cJSON_AddItemToObject(o, "drag", dr);
    cJSON *un = cJSON_CreateObject();
    cJSON_AddNumberToObject(un, "samples", CLI_PAPER_MC_SAMPLES);
    cJSON_AddNumberToObject(un, "seed", CLI_PAPER_MC_SEED);
    cJSON_AddNumberToObject(un, "liftoff_fraction",
                            r->mc_counts.valid ? (double)r->mc_counts.liftoffs / (double)r->mc_counts.valid : 0.0);
    if (r->mc.n > 0) {
        cJSON_AddNumberToObject(un, "p2_5", r->mc.p2_5);
        cJSON_AddNumberToObject(un, "p50", r->mc.p50);
        cJSON_AddNumberToObject(un, "p97_5", r->mc.p97_5);
    }
    cJSON_AddBoolToObject(un, "measured_inside", mc_inside(r));
    cJSON_AddItemToObject(o, "full_uncertainty", un);
    cJSON *me = theta_x(NAN, r->table.measured_x_m);
    cJSON_AddNumberToObject(me, "error", r->table.measured_error_m);
    cJSON_AddItemToObject(o, "measured", me);
    return o;
}

/* The table on standard output, the JSON document into json (NULL: none;
 * "-": standard output, in place of the table). The exit status. */
static int print_rows(const paper_row *rows, int n, const char *json, int stopped)
{
    if (json) {
        cJSON *doc = cJSON_CreateObject();
        cJSON *setup_json = cli_json_setup(&rows[0].model);
        cJSON_DeleteItemFromObject(setup_json, "incline_deg"); /* per row */
        cJSON_AddItemToObject(doc, "setup", setup_json);
        cJSON *arr = cJSON_AddArrayToObject(doc, "rows");
        for (int i = 0; i < n; ++i) cJSON_AddItemToArray(arr, json_row(&rows[i]));
        if (stopped) cJSON_AddStringToObject(doc, "stopped_by", cli_signal_name(cli_stop_requested()));
        const int rc = cli_json_write(doc, json);
        if (rc != EXIT_OK || strcmp(json, "-") == 0) return rc;
    }
    print_text(rows, n);
    if (json) printf("JSON written to %s\n", json);
    return cli_stdout_finish();
}

/* The option, as given, that made the body another one than the paper's:
 * the preset, the experiment file, a part, or a body parameter. */
static void body_option(const cli_SetupArgs *sa, char *out, size_t len)
{
    if (sa->preset && strcmp(sa->preset, "paper") != 0) {
        snprintf(out, len, "--preset %s", sa->preset);
        return;
    }
    if (sa->part_count > 0) {
        snprintf(out, len, "--part %s", sa->part_text[0]);
        return;
    }
    for (int id = 0; id < jc_param_count(); ++id)
        if ((jc_param_info(id)->flags & JC_PARAM_BODY) && sa->value[id]) {
            snprintf(out, len, "--%s %s", jc_param_info(id)->name, sa->value[id]);
            return;
        }
    if (sa->config) snprintf(out, len, "--config %s", sa->config);
    else snprintf(out, len, "the setup options");
}

int cli_paper_body_only(const char *cmd, const char *what, const char *instead, const cli_SetupArgs *sa,
                        const jc_Setup *s)
{
    if (jc_paper_body_is(&s->body)) return EXIT_OK;
    char option[256];
    body_option(sa, option, sizeof option);
    cli_error("%s: %s%s gives a body other than the paper's cylinder, the only one its Table 1 measured "
              "(options that keep the body, such as --mu or --paper-d, may change); for this body use "
              "'jumpcyl %s --incline 15' (30, 45)",
              cmd, what, option, instead);
    return EXIT_USAGE;
}

int cmd_paper(int argc, char **argv)
{
    const char *json = NULL;
    cli_SetupArgs sa;
    int st = cli_json_command_parse(argc, argv, help, &json, &sa);
    if (st != CLI_GO_ON) return st;
    if (cli_setup_given(&sa, "incline")) {
        cli_error("paper: --incline is set by the table (15, 30, 45 deg); use 'jumpcyl predict --incline ...'");
        return EXIT_USAGE;
    }
    jc_Setup setup;
    if ((st = cli_build_inputs("paper", &sa, NULL, &setup, NULL, NULL)) != EXIT_OK) return st;
    if ((st = cli_paper_body_only("paper", "", "predict", &sa, &setup)) != EXIT_OK) return st;
    char err[512];
    paper_row rows[ROWS_MAX];
    int n = 0;
    /* A signal stops between runs (signals.c); the rows complete by then are printed. */
    st = compute_rows(&setup, &sa, rows, &n, err, sizeof err);
    const int stopped = st == JC_ESTOPPED;
    if (st != JC_OK && !stopped) {
        cli_error("paper: %s", err);
        return cli_exit_status(st, CLI_INPUTS_GIVEN);
    }
    const int rc = n > 0 ? print_rows(rows, n, json, stopped) : EXIT_OK;
    if (!stopped) return rc;
    cli_error("paper: stopped by %s; %d complete row(s) printed", cli_signal_name(cli_stop_requested()), n);
    return rc == EXIT_OK ? cli_stop_status() : rc;
}
