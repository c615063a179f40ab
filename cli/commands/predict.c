/* jumpcyl predict: the paper's model and the exact rolling model for one setup. */
#include "commands.h"
#include "inputs.h"

#include <cjson/cJSON.h>
#include <string.h>

static void help(void)
{
    puts("Usage: jumpcyl predict [SETUP OPTIONS] [--json FILE]\n"
         "The paper's model (its Eq. 9), the exact rolling model and the full model's first\n"
         "lift-off for one setup.\n"
         "\n"
         "  --json FILE machine-readable output into FILE (- or no FILE: standard output, in\n"
         "              place of the text): paper_model.roots (rad), rolling.liftoff and\n"
         "              rolling.slip, each null or {theta (rad), x (m), omega (rad/s),\n"
         "              normal (N), friction (N)}; full.liftoff {theta, x, t} or null, full.hops;\n"
         "              x is the centre's travel along the incline\n"
         "  -h, --help  this help\n");
}

static void print_crossing(const char *label, const jc_RollingCrossing *c)
{
    if (!c->found) {
        printf("  %-34s none on the rolling path\n", label);
        return;
    }
    const jc_RollingState *s = &c->state;
    printf("  %-34s th = %9.5f rad  x = %7.2f cm  w = %7.3f rad/s  N = %8.5f N  F = %8.5f N%s\n",
           label, cli_shown(s->theta_rad, 5), cli_shown(s->x_m * 100, 2), cli_shown(s->omega_radps, 3),
           cli_shown(s->normal_N, 5), cli_shown(s->friction_N, 5),
           c->grazing ? "  (grazing)" : "");
}

static void print_full(const jc_Run *run)
{
    jc_RunSummary sum;
    jc_run_summarize(run, &sum);
    printf("\nFull model (slip, flight, impacts; 'jumpcyl simulate' shows every event):\n");
    if (sum.first_liftoff < 0) {
        printf("  no lift-off before the run ended (%s)\n", jc_termination_name(run->termination));
        return;
    }
    const jc_Event *e = &run->events[sum.first_liftoff];
    printf("  first lift-off:                    th = %9.5f rad  x = %7.2f cm  t = %.5f s  from %s\n",
           e->state.theta_rad, e->state.x_m * 100, e->state.t_s, jc_mode_name(e->mode_before));
    printf("  hops on the ramp: %d lift-off(s), %d bounce(s); largest hop %.2f mm; run ended: %s\n",
           sum.liftoffs, sum.bounces, sum.largest_hop_m * 1e3, jc_termination_name(run->termination));
}

static void print_text(const jc_Model *m, const jc_PaperResult *p, const jc_RollingResult *r, const jc_Run *run)
{
    cli_print_setup(stdout, m, 1);
    printf("\nPaper's model (Eq. 9 as printed; d = %.4f cm, M1 = %.2f g; starts at rest at th = 0):\n",
           p->cm_offset_m * 100, p->disc_mass_kg * 1e3);
    if (m->setup.theta0_rad != 0.0 || m->setup.omega0_radps != 0.0)
        printf("  note: this model ignores theta0 = %.4g deg and omega0 = %.4g rad/s; the exact models use them\n",
               cli_deg(m->setup.theta0_rad), m->setup.omega0_radps);
    if (p->first < 0) {
        printf("  no intersection before the ramp end: the paper's model predicts no jump\n");
    } else {
        printf("  first intersection (its jump):     th = %9.5f rad  x = %7.2f cm\n",
               p->theta_rad[p->first], p->x_m[p->first] * 100);
        printf("  all intersections (rad):          ");
        for (int i = 0; i < p->root_count; ++i) printf(" %.4f", p->theta_rad[i]);
        printf("%s\n", p->truncated ? " ..." : "");
    }
    printf("\nExact rolling model (rolls without slipping; closed form, roots to 1e-12 rad):\n");
    char label[64];
    snprintf(label, sizeof label, "slip onset |F| = mu_s N (%.3g):", m->setup.mu_static);
    print_crossing(label, &r->slip);
    print_crossing("N = 0 on the rolling path:", &r->liftoff);
    printf("  rolling path ends:                 %s at x = %.2f cm\n", jc_rolling_end_name(r->end),
           r->end_x_m * 100);
    print_full(run);
    if (r->liftoff.found)
        printf("\nNote: the rolling N = 0 point is a diagnostic, not the physical jump: there F = %.4g N,\n"
               "not 0, so with any finite friction the cylinder slips before it (|F|/N grows without\n"
               "bound as N -> 0), and the real lift-off happens from sliding (docs/physics.md).\n",
               r->liftoff.state.friction_N);
}

static cJSON *json_doc(const jc_Model *m, const jc_PaperResult *p, const jc_RollingResult *r, const jc_Run *run)
{
    cJSON *doc = cJSON_CreateObject();
    cJSON_AddItemToObject(doc, "setup", cli_json_setup(m));
    cJSON *pm = cJSON_AddObjectToObject(doc, "paper_model");
    cJSON_AddNumberToObject(pm, "cm_offset", p->cm_offset_m);
    cJSON_AddNumberToObject(pm, "disc_mass", p->disc_mass_kg);
    cJSON_AddItemToObject(pm, "roots", cJSON_CreateDoubleArray(p->theta_rad, p->root_count));
    cJSON_AddBoolToObject(pm, "truncated", p->truncated);
    if (p->first >= 0) {
        cJSON *f = cJSON_AddObjectToObject(pm, "first");
        cJSON_AddNumberToObject(f, "theta", p->theta_rad[p->first]);
        cJSON_AddNumberToObject(f, "x", p->x_m[p->first]);
    } else {
        cJSON_AddNullToObject(pm, "first");
    }
    cJSON *ro = cJSON_AddObjectToObject(doc, "rolling");
    cJSON_AddItemToObject(ro, "liftoff", cli_json_crossing(&r->liftoff));
    cJSON_AddItemToObject(ro, "slip", cli_json_crossing(&r->slip));
    cJSON_AddStringToObject(ro, "end", jc_rolling_end_name(r->end));
    cJSON_AddNumberToObject(ro, "end_x", r->end_x_m);
    jc_RunSummary sum;
    jc_run_summarize(run, &sum);
    cJSON *fu = cJSON_AddObjectToObject(doc, "full");
    if (sum.first_liftoff >= 0) {
        const jc_Event *e = &run->events[sum.first_liftoff];
        cJSON *lo = cJSON_AddObjectToObject(fu, "liftoff");
        cJSON_AddNumberToObject(lo, "theta", e->state.theta_rad);
        cJSON_AddNumberToObject(lo, "x", e->state.x_m);
        cJSON_AddNumberToObject(lo, "t", e->state.t_s);
    } else {
        cJSON_AddNullToObject(fu, "liftoff");
    }
    cJSON_AddNumberToObject(fu, "hops", sum.liftoffs);
    cJSON_AddNumberToObject(fu, "bounces", sum.bounces);
    cJSON_AddNumberToObject(fu, "largest_hop", sum.largest_hop_m);
    cJSON_AddStringToObject(fu, "termination", jc_termination_name(run->termination));
    return doc;
}

int cmd_predict(int argc, char **argv)
{
    const char *json = NULL;
    cli_SetupArgs sa;
    int st = cli_json_command_parse(argc, argv, help, &json, &sa);
    if (st != CLI_GO_ON) return st;

    jc_Model model;
    if ((st = cli_build_model("predict", &sa, NULL, NULL, &model)) != EXIT_OK) return st;
    char err[512];
    jc_PaperResult paper;
    jc_RollingResult rolling;
    if ((st = jc_paper_solve(&model, &paper, err, sizeof err)) != JC_OK ||
        (st = jc_rolling_predict(&model, &rolling, err, sizeof err)) != JC_OK) {
        cli_error("predict: %s", err);
        return cli_exit_status(st, CLI_INPUTS_GIVEN);
    }
    const jc_SimOptions sim = jc_default_sim_options();
    jc_Run run;
    if ((st = cli_simulate(&model, &sim, &run, "predict")) != JC_OK) {
        jc_run_free(&run);
        return cli_exit_status(st, CLI_INPUTS_CHECKED);
    }
    int rc = json ? cli_json_write(json_doc(&model, &paper, &rolling, &run), json) : EXIT_OK;
    if (rc == EXIT_OK && !(json && strcmp(json, "-") == 0)) {
        print_text(&model, &paper, &rolling, &run);
        if (json) printf("JSON written to %s\n", json);
        rc = cli_stdout_finish();
    }
    jc_run_free(&run);
    return rc;
}
