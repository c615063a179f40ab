/* jumpcyl simulate: the full motion down the ramp, as an event table. */
#include "cli.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <string.h>

typedef struct {
    int json;
    const char *csv;
} simulate_opts;

static void help(void)
{
    puts("Usage: jumpcyl simulate [SETUP OPTIONS] [SIMULATION OPTIONS] [--json] [--csv FILE]\n"
         "The full motion: rolling, slipping, lift-off, flight, impacts and further hops,\n"
         "until the ramp's end or a limit. Every mode change is an event located in time.\n"
         "\n"
         "  --json      {\"events\": [...], \"termination\": ..., \"energy\": {...}, ...};\n"
         "              each event has kind, t (s), x (m, centre along the incline from its\n"
         "              start), y (m, centre above the incline), theta (rad), omega (rad/s),\n"
         "              slip (m/s), normal and friction (N, just before); a liftoff or a\n"
         "              bounce into flight also flight_time (s), hop_height (m), landing_x (m)\n"
         "  --csv FILE  write the trajectory (samples every --sample-dt and at every event)\n"
         "  -h, --help  this help\n");
    cli_sim_help(stdout);
    putchar('\n');
    cli_setup_help(stdout);
}

static int take(int opt, const char *arg, void *ctx)
{
    simulate_opts *o = ctx;
    if (opt == 'j') { o->json = 1; return 0; }
    if (opt == 'c') { o->csv = arg; return 0; }
    if (opt == 'h') { help(); return -1; }
    return EXIT_USAGE;
}

static int write_csv(const jc_Run *run, const char *path)
{
    cli_AtomicFile af;
    if (cli_atomic_open(&af, path) != 0) return EXIT_FAIL;
    fprintf(af.f, "t_s,mode,x_m,y_m,vx_mps,vy_mps,theta_rad,omega_radps,cm_x_m,cm_y_m,normal_N,friction_N,"
                  "slip_mps,gap_m,kinetic_J,potential_J,friction_loss_J,impact_loss_J,air_loss_J,rolling_resistance_loss_J\n");
    for (int i = 0; i < run->sample_count; ++i) {
        const jc_Sample *p = &run->samples[i];
        const jc_State *s = &p->state;
        fprintf(af.f, "%.12g,%s,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.9g,%.9g,%.9g,%.9g,%.12g,%.12g,%.9g,%.9g,%.9g,%.9g\n",
                s->t_s, jc_mode_name(p->mode), s->x_m, s->y_m, s->vx_mps, s->vy_mps, s->theta_rad, s->omega_radps,
                p->cm_x_m, p->cm_y_m, p->normal_N, p->friction_N, p->slip_mps, p->gap_m, p->kinetic_J,
                p->potential_J, p->friction_loss_J, p->impact_loss_J, p->air_loss_J, p->rolling_resistance_loss_J);
    }
    return cli_atomic_commit(&af) == 0 ? EXIT_OK : EXIT_FAIL;
}

static void print_event(const jc_Model *m, int i, const jc_Event *e)
{
    const jc_State *s = &e->state;
    char change[32];
    snprintf(change, sizeof change, "%s->%s", jc_mode_name(e->mode_before), jc_mode_name(e->mode_after));
    printf("%3d %-13s %-17s %9.6f %8.2f %8.3f %9.4f %9.3f %8.4f %8.4f %8.4f", i + 1, jc_event_name(e->kind), change,
           s->t_s, s->x_m * 100, (s->y_m - m->body.radius_m) * 1e3, s->theta_rad, s->omega_radps, e->slip_mps, e->normal_N,
           e->friction_N);
    if (e->kind == JC_EVENT_TOUCHDOWN || e->kind == JC_EVENT_BOUNCE) printf("  impact %.3f m/s;", e->impact_speed_mps);
    if (e->kind == JC_EVENT_LIFTOFF || (e->kind == JC_EVENT_BOUNCE && e->mode_after == JC_MODE_FLIGHT)) {
        printf("  flight %.4f s, hop %.3f mm", e->flight_time_s, e->hop_height_m * 1e3);
        if (!isnan(e->landing_x_m)) printf(", lands at %.2f cm", e->landing_x_m * 100);
        else printf(", still in flight at the end");
    }
    putchar('\n');
}

static const char *law_title(jc_ImpactLaw law)
{
    switch (law) {
    case JC_IMPACT_STRONGE: return "Stronge";
    case JC_IMPACT_POISSON: return "Poisson";
    case JC_IMPACT_NEWTON: return "Newton";
    }
    return "unknown";
}

/* Poisson's and Newton's laws can create energy at an impact (docs/physics.md
 * §4): said on standard error, with the energy, whatever the output format. */
static void warn_energy_gain(const jc_Model *m, const jc_Run *run)
{
    if (run->energy_gaining_impacts <= 0) return;
    fprintf(stderr,
            "jumpcyl: simulate: warning: %d impact(s) gained kinetic energy under %s's law (largest gain\n"
            "  %+.6g J); Stronge's law (--impact-law stronge) never creates energy (docs/physics.md, section 4)\n",
            run->energy_gaining_impacts, law_title(m->setup.impact_law), run->largest_impact_gain_J);
}

static void print_text(const jc_Model *m, const jc_SimOptions *o, const jc_Run *run)
{
    cli_print_setup(stdout, m, 1);
    if (jc_setup_has_resistance(&m->setup))
        printf("Full model with air and rolling resistance (C_d %g, C_L %g, spin drag %g N m s2, lever %g m;\n"
               "rho %g kg/m3, length %g m): every phase integrated (rk8pd, rtol %g), impacts (%s's law,\n"
               "restitution %g, Coulomb friction); events located to %g s; bounces rising less than %g m end\n"
               "in contact.\n\n",
               m->setup.drag_coefficient, m->setup.lift_coefficient, m->setup.spin_drag_Nms2,
               m->setup.rolling_resistance_m, m->setup.air_density_kgpm3, m->setup.length_m, o->ode_rtol,
               law_title(m->setup.impact_law), m->setup.restitution, o->event_tol_s, o->contact_height_m);
    else
        printf("Full model: rolling (closed form), sliding (rk8pd, rtol %g), flight (ballistic), impacts\n"
               "(%s's law, restitution %g, Coulomb friction); events located to %g s; bounces rising\n"
               "less than %g m end in contact.\n\n",
               o->ode_rtol, law_title(m->setup.impact_law), m->setup.restitution, o->event_tol_s,
               o->contact_height_m);
    printf("  # event         mode change           t (s)   x (cm) gap (mm) theta(rad) w (rad/s) slip(m/s)    N (N)    F (N)\n");
    for (int i = 0; i < run->event_count; ++i) print_event(m, i, &run->events[i]);
    if (run->event_count == 0) printf("  (no events)\n");
    const jc_State *f = &run->final_state;
    printf("\nRun ended: %s (%s) at t = %.6f s, x = %.2f cm, in %s.\n", jc_termination_name(run->termination),
           run->termination_detail, f->t_s, f->x_m * 100, jc_mode_name(run->final_mode));
    const jc_EnergyReport *e = &run->energy;
    /* Relative to the energy that changed hands, or to M g r for a body that hardly moved. */
    const double losses = e->friction_loss_J + e->impact_loss_J + e->air_loss_J + e->rolling_resistance_loss_J;
    const double scale = fmax(e->kinetic_J + fabs(e->potential_J) + losses,
                              m->body.mass_kg * m->setup.gravity_mps2 * m->body.radius_m);
    printf("Energy (J): kinetic %.6f, potential %.6f (from the start); lost to friction %.6f, in impacts %.6f,\n"
           "            to the air %.6f, to rolling resistance %.6f; balance error %.2e J (%.1e relative)\n",
           e->kinetic_J, e->potential_J, e->friction_loss_J, e->impact_loss_J, e->air_loss_J,
           e->rolling_resistance_loss_J, e->balance_error_J, fabs(e->balance_error_J) / scale);
    jc_RunSummary sum;
    jc_run_summarize(run, &sum);
    if (sum.first_liftoff >= 0) {
        const jc_Event *l = &run->events[sum.first_liftoff];
        printf("First lift-off at x = %.2f cm (theta = %.4f rad, t = %.4f s); %d lift-off(s), %d bounce(s);\n"
               "largest hop %.2f mm (event %d).\n",
               l->state.x_m * 100, l->state.theta_rad, l->state.t_s, sum.liftoffs, sum.bounces,
               sum.largest_hop_m * 1e3, sum.largest_hop + 1);
    } else {
        printf("No lift-off.\n");
    }
}

static cJSON *json_doc(const jc_Model *m, const jc_Run *run)
{
    cJSON *doc = cJSON_CreateObject();
    cJSON_AddItemToObject(doc, "setup", cli_json_setup(m));
    cJSON *ev = cJSON_AddArrayToObject(doc, "events");
    for (int i = 0; i < run->event_count; ++i) cJSON_AddItemToArray(ev, cli_json_event(&run->events[i]));
    cJSON_AddStringToObject(doc, "termination", jc_termination_name(run->termination));
    cJSON_AddStringToObject(doc, "termination_detail", run->termination_detail);
    cJSON_AddNumberToObject(doc, "t_end", run->final_state.t_s);
    cJSON_AddItemToObject(doc, "energy", cli_json_energy(&run->energy));
    cJSON_AddStringToObject(doc, "impact_law", jc_impact_law_name(m->setup.impact_law));
    cJSON_AddNumberToObject(doc, "energy_gaining_impacts", run->energy_gaining_impacts);
    cJSON_AddNumberToObject(doc, "largest_impact_gain_J", run->largest_impact_gain_J);
    jc_RunSummary sum;
    jc_run_summarize(run, &sum);
    cJSON *s = cJSON_AddObjectToObject(doc, "summary");
    cJSON_AddNumberToObject(s, "liftoffs", sum.liftoffs);
    cJSON_AddNumberToObject(s, "bounces", sum.bounces);
    cJSON_AddNumberToObject(s, "largest_hop", sum.largest_hop_m);
    if (sum.first_liftoff >= 0) {
        cJSON_AddNumberToObject(s, "first_liftoff_x", run->events[sum.first_liftoff].state.x_m);
        cJSON_AddNumberToObject(s, "first_liftoff_theta", run->events[sum.first_liftoff].state.theta_rad);
    } else {
        cJSON_AddNullToObject(s, "first_liftoff_x");
        cJSON_AddNullToObject(s, "first_liftoff_theta");
    }
    return doc;
}

int cmd_simulate(int argc, char **argv)
{
    static const struct option own[] = {{"json", no_argument, 0, 'j'},
                                        {"csv", required_argument, 0, 'c'},
                                        {"help", no_argument, 0, 'h'}};
    simulate_opts o = {0};
    cli_SetupArgs sa;
    cli_SimArgs sim_args;
    int st = cli_parse_args(argc, argv, own, 3, take, &o, &sa, &sim_args);
    if (st) return st < 0 ? EXIT_OK : st;
    char err[512];
    jc_Setup setup;
    jc_SimOptions opts;
    if (cli_setup_build(&sa, &setup, err, sizeof err) != 0 || cli_sim_build(&sim_args, &opts, err, sizeof err) != 0) {
        cli_error("simulate: %s", err);
        return EXIT_USAGE;
    }
    jc_Model model;
    if ((st = jc_model_init(&model, &setup, err, sizeof err)) != JC_OK) {
        cli_error("simulate: %s", err);
        return st == JC_EINVAL ? EXIT_USAGE : EXIT_FAIL;
    }
    jc_Run run;
    if (cli_simulate(&model, &opts, &run, "simulate") != JC_OK) {
        jc_run_free(&run);
        return EXIT_FAIL;
    }
    int rc = EXIT_OK;
    warn_energy_gain(&model, &run);
    if (o.csv) rc = write_csv(&run, o.csv);
    if (rc == EXIT_OK) {
        if (o.json) rc = cli_json_print(json_doc(&model, &run));
        else {
            print_text(&model, &opts, &run);
            if (o.csv) printf("Trajectory: %d samples written to %s\n", run.sample_count, o.csv);
            rc = cli_stdout_finish();
        }
    }
    jc_run_free(&run);
    return rc;
}
