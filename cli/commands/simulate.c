/* jumpcyl simulate: the full motion down the ramp, as an event table. */
#include "commands.h"
#include "inputs.h"

#include <errno.h>
#include <math.h>
#include <string.h>

typedef struct {
    const char *json, *csv; /* their files, "-" for standard output; NULL: none */
} simulate_opts;

static void help(void)
{
    puts("Usage: jumpcyl simulate [SETUP OPTIONS] [SIMULATION OPTIONS] [--json FILE] [--csv FILE]\n"
         "The full motion: rolling, slipping, lift-off, flight, impacts and further hops,\n"
         "until the ramp's end or a limit. Every mode change is an event located in time.\n"
         "\n"
         "  --json FILE the run as JSON into FILE (- or no FILE: standard output, in place of\n"
         "              the table): {\"events\": [...], \"termination\": ..., \"energy\": {...}, ...};\n"
         "              each event has kind, t (s), x (m, centre along the incline from its\n"
         "              start), y (m, centre above the incline), theta (rad), omega (rad/s),\n"
         "              slip (m/s), normal and friction (N, just before); a liftoff or a\n"
         "              bounce into flight also flight_time (s), hop_height (m), landing_x (m)\n"
         "  --csv FILE  write the trajectory (samples every --sample-dt and at every event);\n"
         "              - is standard output, in place of the table\n"
         "  -h, --help  this help\n");
}

static int take(int opt, const char *arg, void *ctx)
{
    simulate_opts *o = ctx;
    if (opt == 'j') { o->json = arg; return CLI_GO_ON; }
    if (opt == 'c') { o->csv = arg; return CLI_GO_ON; }
    return EXIT_USAGE;
}

/* The command's own options; the setup and simulation options come with cli_command_parse. */
static const struct option own[] = {CLI_JSON_OPTION('j'),
                                    {"csv", required_argument, 0, 'c'},
                                    {"help", no_argument, 0, 'h'}};
static const cli_Command command = {own, (int)(sizeof own / sizeof own[0]), take, help};

/* The first write that failed, which stops the run: where, and why (the
 * errno, gone once the stream's buffer is dropped). */
typedef enum { WRITES_OK, FAILED_STDOUT, FAILED_CSV, FAILED_JSON, FAILED_JSON_MEMORY } write_target;
typedef struct {
    write_target where;
    int err; /* the errno of a failed write to standard output, the CSV or the JSON file */
} write_failure;

/* Everything simulate writes while the run goes on: events to the table
 * on standard output and to the JSON document, samples to the CSV. Nothing
 * is kept, so memory does not grow with the run. */
typedef struct {
    const jc_Model *model;
    int text;
    cli_Output *json;    /* NULL without --json */
    cli_Output *csv;     /* NULL without --csv */
    jc_RunSummary sum;
    int events;
    write_failure failed;
} sim_stream;

/* Records a failure, unless an earlier one is recorded. */
static void note_failure(sim_stream *st, write_target where, int err)
{
    if (st->failed.where == WRITES_OK) st->failed = (write_failure){where, err};
}

/* A failed write to standard output, noted while its reason is known. */
static void check_stdout(sim_stream *st)
{
    if (ferror(stdout)) note_failure(st, FAILED_STDOUT, errno ? errno : EIO);
}

/* A failed write to the JSON file (standard output's is check_stdout's). */
static void check_json(sim_stream *st)
{
    if (st->json && !st->json->is_stdout && ferror(st->json->f)) note_failure(st, FAILED_JSON, errno ? errno : EIO);
}

/* The recorder's answer: a failed write stops the run at once instead of
 * computing for nothing. */
static int go_on(const sim_stream *st) { return st->failed.where == WRITES_OK ? JC_OK : JC_ESTOPPED; }

/* Said on standard error, but not a closed pipe's: its reader went away
 * (cli_pipe_closed), and the command ends quietly. */
static void report_failure(const sim_stream *st)
{
    const write_failure *f = &st->failed;
    const cli_Output *file = f->where == FAILED_CSV ? st->csv : f->where == FAILED_JSON ? st->json : NULL;
    if ((f->where == FAILED_STDOUT || (file && file->is_stdout)) && cli_pipe_closed(f->err)) return;
    if (file) cli_error("cannot write %s: %s", file->is_stdout ? "standard output" : file->target, strerror(f->err));
    else if (f->where == FAILED_STDOUT) cli_error("cannot write standard output: %s", strerror(f->err));
    else if (f->where == FAILED_JSON_MEMORY) cli_error("simulate: out of memory for the JSON document");
}

/* The trajectory CSV: the library's sample columns (jc_sample_column_info),
 * named with their units, a row per sample (jc_sample_format_row). */
static void csv_header(FILE *f)
{
    for (int c = 0; c < JC_SAMPLE_COLUMNS; ++c) {
        if (c) fputc(',', f);
        fputs(jc_sample_column_info(c)->name, f);
    }
    fputc('\n', f);
}

static int on_sample(void *ctx, const jc_Sample *p)
{
    sim_stream *st = ctx;
    FILE *f = st->csv->f;
    char row[JC_SAMPLE_ROW_MAX + 1];
    size_t n = (size_t)jc_sample_format_row(p, row, sizeof row - 1);
    row[n++] = '\n';
    fwrite(row, 1, n, f);
    if (ferror(f)) note_failure(st, FAILED_CSV, errno ? errno : EIO); /* fwrite's reason: ENOSPC, EFBIG */
    return go_on(st);
}

static void print_event(const jc_Model *m, int i, const jc_Event *e)
{
    const jc_State *s = &e->state;
    char change[32];
    snprintf(change, sizeof change, "%s->%s", jc_mode_name(e->mode_before), jc_mode_name(e->mode_after));
    printf("%3d %-13s %-17s %9.6f %8.2f %8.3f %9.4f %9.3f %8.4f %8.4f %8.4f", i + 1, jc_event_name(e->kind), change,
           s->t_s, cli_shown(s->x_m * 100, 2), cli_shown((s->y_m - m->body.radius_m) * 1e3, 3),
           cli_shown(s->theta_rad, 4), cli_shown(s->omega_radps, 3), cli_shown(e->slip_mps, 4),
           cli_shown(e->normal_N, 4), cli_shown(e->friction_N, 4));
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

static void print_head(const jc_Model *m, const jc_SimOptions *o)
{
    cli_print_setup(stdout, m, 1);
    if (jc_setup_has_resistance(&m->setup))
        printf("Full model with air and rolling resistance (C_d %g, C_L %g, spin drag %g N m s2, lever %g m;\n"
               "rho %g kg/m3, length %g m): every phase integrated (DOP853, rtol %g), impacts (%s's law,\n"
               "restitution %g, Coulomb friction); events located to %g s; bounces rising less than %g m end\n"
               "in contact.\n\n",
               m->setup.drag_coefficient, m->setup.lift_coefficient, m->setup.spin_drag_Nms2,
               m->setup.rolling_resistance_m, m->setup.air_density_kgpm3, m->setup.length_m, o->ode_rtol,
               law_title(m->setup.impact_law), m->setup.restitution, o->event_tol_s, o->contact_height_m);
    else
        printf("Full model: rolling (closed form), sliding (DOP853, rtol %g), flight (ballistic), impacts\n"
               "(%s's law, restitution %g, Coulomb friction); events located to %g s; bounces rising\n"
               "less than %g m end in contact.\n\n",
               o->ode_rtol, law_title(m->setup.impact_law), m->setup.restitution, o->event_tol_s,
               o->contact_height_m);
    printf("  # event         mode change           t (s)   x (cm) gap (mm) theta(rad) w (rad/s) slip(m/s)    N (N)    F (N)\n");
}

static void print_tail(const jc_Model *m, const jc_Run *run, const jc_RunSummary *sum)
{
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
    if (sum->first_liftoff >= 0) {
        const jc_State *l = &sum->first_liftoff_state;
        printf("First lift-off at x = %.2f cm (theta = %.4f rad, t = %.4f s); %d lift-off(s), %d bounce(s);\n"
               "largest hop %.2f mm (event %d).\n",
               l->x_m * 100, l->theta_rad, l->t_s, sum->liftoffs, sum->bounces, sum->largest_hop_m * 1e3,
               sum->largest_hop + 1);
    } else {
        printf("No lift-off.\n");
    }
}

static int on_event(void *ctx, const jc_Event *e)
{
    sim_stream *st = ctx;
    if (st->json) cli_sim_json_event(st->json->f, e, st->events);
    if (st->text) print_event(st->model, st->events, e);
    jc_summary_add(&st->sum, e, st->events);
    st->events++;
    check_stdout(st);
    check_json(st);
    return go_on(st);
}

/* The CSV opened and its header written: EXIT_OK, or EXIT_FAIL after a message. */
static int csv_open(cli_Output *csv, const char *name)
{
    if (cli_output_begin(csv, name, 1) != 0) return EXIT_FAIL;
    csv_header(csv->f);
    /* A device that takes nothing (/dev/full) fails here, before the
     * table starts on standard output. */
    if (csv->in_place && fflush(csv->f) != 0) {
        const int err = errno;
        if (!(csv->is_stdout && cli_pipe_closed(err)))
            cli_error("cannot write %s: %s", csv->is_stdout ? "standard output" : name, strerror(err));
        cli_output_abort(csv);
        return cli_stop_requested() ? cli_stop_status() : EXIT_FAIL;
    }
    return EXIT_OK;
}

/* The files dropped: the CSV and the JSON file (not standard output). */
static void abort_files(const sim_stream *out)
{
    if (out->csv) cli_output_abort(out->csv);
    if (out->json) cli_output_abort(out->json);
}

/* A run that did not end well (st, a library status): the failed write
 * said (a file's even after a stop signal), the files dropped. The exit status. */
static int run_failed(const sim_stream *out, int st)
{
    const int file_failed = out->failed.where == FAILED_CSV || out->failed.where == FAILED_JSON;
    if (file_failed) report_failure(out);
    abort_files(out);
    if (cli_stop_requested()) return cli_stop_status();
    if (!file_failed) report_failure(out);
    return cli_exit_status(st, CLI_INPUTS_CHECKED);
}

/* The CSV and the JSON file, each made whole, then both published: neither
 * or both appear. EXIT_OK, or EXIT_FAIL after a message. */
static int publish_files(const sim_stream *out)
{
    cli_Output *f[2] = {out->csv, out->json && !out->json->is_stdout ? out->json : NULL};
    int ok = 1;
    for (int k = 0; k < 2 && ok; ++k) ok = !f[k] || cli_output_finish(f[k], CLI_CHECK_WRITES) == 0;
    for (int k = 0; k < 2 && ok; ++k) ok = !f[k] || cli_output_publish(f[k]) == 0;
    abort_files(out);
    return ok ? EXIT_OK : EXIT_FAIL;
}

/* The table's or the document's end after a run that ended well, the
 * files published. The exit status. */
static int run_done(sim_stream *out, const jc_Run *run, const cli_RunInputs *in, const char *csv_name)
{
    warn_energy_gain(&in->model, run);
    if (out->json) {
        cli_sim_json_end(out->json->f, &in->model, run, &out->sum);
        check_json(out);
    }
    if (out->failed.where == WRITES_OK && publish_files(out) != EXIT_OK)
        return cli_stop_requested() ? cli_stop_status() : EXIT_FAIL;
    if (out->text) {
        print_tail(&in->model, run, &out->sum);
        if (csv_name) printf("Trajectory: %d samples written to %s\n", run->sample_count, csv_name);
        if (out->json) printf("JSON written to %s\n", out->json->target);
    }
    check_stdout(out);
    if (out->failed.where != WRITES_OK) {
        report_failure(out);
        abort_files(out);
        return cli_stop_requested() ? cli_stop_status() : EXIT_FAIL;
    }
    if (run->termination == JC_END_SAMPLE_LIMIT)
        cli_error("simulate: the run stopped at the sample limit (%d samples); raise --sample-dt or lower --t-max",
                  in->sim.max_samples);
    return cli_stdout_finish();
}

/* --csv and --json: not both standard output, not one file. EXIT_OK or
 * EXIT_USAGE after a message. */
static int check_files(const simulate_opts *o)
{
    if (!o->csv || !o->json) return EXIT_OK;
    if (strcmp(o->csv, "-") == 0 && strcmp(o->json, "-") == 0) {
        cli_error("simulate: --csv - and --json would both write to standard output; give one of them a file");
        return EXIT_USAGE;
    }
    if (strcmp(o->csv, o->json) == 0) {
        cli_error("simulate: --csv and --json name the same file");
        return EXIT_USAGE;
    }
    return EXIT_OK;
}

int cmd_simulate(int argc, char **argv)
{
    simulate_opts o = {0};
    cli_RunInputs in;
    int st = cli_run_inputs_parse(argc, argv, &command, &o, &in);
    if (st != CLI_GO_ON) return st;
    if ((st = cli_run_inputs_build("simulate", &in)) != EXIT_OK) return st;
    if ((st = check_files(&o)) != EXIT_OK) return st;
    cli_Output csv, json;
    memset(&csv, 0, sizeof csv);
    memset(&json, 0, sizeof json);
    sim_stream out = {&in.model, 1, NULL, o.csv ? &csv : NULL, {0}, 0, {WRITES_OK, 0}};
    jc_summary_init(&out.sum);
    if (o.csv && (st = csv_open(&csv, o.csv)) != EXIT_OK) return st;
    if (o.json && cli_output_begin(&json, o.json, 1) != 0) {
        cli_output_abort(&csv);
        return EXIT_FAIL;
    }
    if (o.json) out.json = &json;
    /* standard output carries the CSV or the document alone */
    if (csv.is_stdout || json.is_stdout) out.text = 0;
    const int json_failed = out.json && cli_sim_json_begin(json.f, &in.model) != 0;
    if (out.text) print_head(&in.model, &in.sim);
    check_stdout(&out);
    check_json(&out);
    if (json_failed) note_failure(&out, FAILED_JSON_MEMORY, 0); /* unless a write failed */
    const jc_Recorder rec = {&out, on_event, o.csv ? on_sample : NULL};
    jc_Run run;
    st = go_on(&out) != JC_OK ? JC_ESTOPPED : cli_simulate_stream(&in.model, &in.sim, &rec, &run, "simulate");
    if (st != JC_OK) return run_failed(&out, st);
    return run_done(&out, &run, &in, o.csv);
}
