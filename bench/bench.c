/*
 * jumpcyl benchmarks: median wall time per full simulation of the paper's
 * cylinder down its 3.2 m ramp (15, 30, 45 deg), per rolling-model
 * prediction and per paper-model solve, single thread, with the accuracy the
 * default tolerances reach (first lift-off against a run with tolerances
 * 100 times tighter). Given the tool's path (and an MPI build's), it also
 * times the batch commands end to end: simulations per second of `sweep`
 * and `mc` on 1 and 2 threads and under `mpirun -n 2`, and samples per
 * second of `mc --incline 15 --output` (mc_samples_per_s). With
 * JC_BENCH_PYTHON_US set (make bench: python/bench_simulate.py, the same
 * runs through the Python package), it reports python_simulate_us and its
 * ratio to the C call. The last line is one JSON object.
 */
#define _POSIX_C_SOURCE 200809L
#include <jumpcyl/jumpcyl.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <spawn.h>
#include <string.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <time.h>
#include <unistd.h>

extern char **environ;

static double now_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e6 + (double)ts.tv_nsec * 1e-3;
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static void die(const char *what, const char *err)
{
    fprintf(stderr, "bench: %s: %s\n", what, err);
    exit(1);
}

/* First lift-off time and position of a run; NAN if none. */
static void first_liftoff(const jc_Run *run, double *t, double *x)
{
    jc_RunSummary s;
    jc_run_summarize(run, &s);
    *t = s.first_liftoff >= 0 ? run->events[s.first_liftoff].state.t_s : NAN;
    *x = s.first_liftoff >= 0 ? run->events[s.first_liftoff].state.x_m : NAN;
}

#define SIM_REPS 400

/* SIM_REPS runs of a setup: their times (us) and the last run, kept. */
static void time_runs(const jc_Setup *s, double t_sim[SIM_REPS], jc_Model *m, jc_Run *last)
{
    char err[256];
    if (jc_model_init(m, s, err, sizeof err)) die("model", err);
    const jc_SimOptions o = jc_default_sim_options();
    for (int i = 0; i < SIM_REPS; ++i) {
        const double t0 = now_us();
        if (jc_simulate(m, &o, last, err, sizeof err)) die("simulate", err);
        t_sim[i] = now_us() - t0;
        if (i < SIM_REPS - 1) jc_run_free(last);
    }
}
#define BATCH 200
#define BATCHES 200

/* Wall time (s) of a command run with its output to /dev/null; -1 if it failed. */
static double time_command(char *const argv[])
{
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
    pid_t pid;
    const double t0 = now_us();
    const int st = posix_spawnp(&pid, argv[0], &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    int ws = 0;
    if (st != 0 || waitpid(pid, &ws, 0) != pid || !WIFEXITED(ws) || WEXITSTATUS(ws) != 0) return -1;
    return (now_us() - t0) * 1e-6;
}

/* Cases of the batch benchmarks: the paper's cylinder at 30 degrees, a sweep
 * over theta0 and a Monte Carlo job of its default spreads. */
#define BATCH_SWEEP_CASES 200001
#define BATCH_SWEEP_VARY "theta0=0:1:0.000005"
#define BATCH_MC_SAMPLES "100000"
/* The Monte Carlo job of issue 27's goal (10^6 samples in 15 s on 2 cores):
 * the paper's default spreads at 15 deg, every row written (--output), on
 * every core. */
#define BATCH_MC_OUTPUT_SAMPLES "200000"

typedef struct {
    double sweep[2], mc[2], sweep_mpi; /* simulations per second; 1 and 2 threads */
    double mc_output;                  /* samples per second: mc --incline 15 --output, every core */
} batch_rates;

static double rate(double cases, double seconds) { return seconds > 0 ? cases / seconds : -1; }

static void time_batch(const char *cli, const char *mpi_cli, batch_rates *r)
{
    char out[] = "/tmp/jc_bench_XXXXXX";
    const int fd = mkstemp(out);
    if (fd < 0) die("batch", "no temporary file");
    close(fd);
    for (int t = 0; t < 2; ++t) {
        char threads[8];
        snprintf(threads, sizeof threads, "%d", t + 1);
        remove(out);
        char *sweep[] = {(char *)cli, "sweep", "--vary", BATCH_SWEEP_VARY, "--threads", threads, "--quiet",
                         "--output", out, NULL};
        r->sweep[t] = rate(BATCH_SWEEP_CASES, time_command(sweep));
        remove(out);
        char *mc[] = {(char *)cli, "mc", "--samples", BATCH_MC_SAMPLES, "--threads", threads, "--quiet", NULL};
        r->mc[t] = rate(atof(BATCH_MC_SAMPLES), time_command(mc));
    }
    remove(out);
    char *mc_out[] = {(char *)cli, "mc", "--samples", BATCH_MC_OUTPUT_SAMPLES, "--incline", "15", "--output", out,
                      "--quiet", NULL};
    r->mc_output = rate(atof(BATCH_MC_OUTPUT_SAMPLES), time_command(mc_out));
    r->sweep_mpi = -1;
    if (mpi_cli) {
        remove(out);
        char *mpi[] = {"mpirun", "-n", "2", "--oversubscribe", "--allow-run-as-root", (char *)mpi_cli, "sweep",
                       "--vary", BATCH_SWEEP_VARY, "--threads", "1", "--quiet", "--output", out, NULL};
        r->sweep_mpi = rate(BATCH_SWEEP_CASES, time_command(mpi));
    }
    remove(out);
    printf("\nbatch commands, paper's cylinder at 30 deg (simulations per second, whole command):\n"
           "  sweep %d cases: %.0f/s on 1 thread, %.0f/s on 2 threads", BATCH_SWEEP_CASES, r->sweep[0], r->sweep[1]);
    if (mpi_cli) printf(", %.0f/s under mpirun -n 2 (1 thread each)", r->sweep_mpi);
    printf("\n  mc %s samples (default spreads): %.0f/s on 1 thread, %.0f/s on 2 threads\n", BATCH_MC_SAMPLES,
           r->mc[0], r->mc[1]);
    printf("  10^6 simulations: %.1f s with sweep on 2 threads\n", 1e6 / r->sweep[1]);
    printf("  mc %s samples at 15 deg, rows written (--output), every core: %.0f/s (10^6 samples in %.1f s)\n",
           BATCH_MC_OUTPUT_SAMPLES, r->mc_output, 1e6 / r->mc_output);
}

int main(int argc, char **argv)
{
    const char *cli = argc > 1 ? argv[1] : NULL, *mpi_cli = argc > 2 ? argv[2] : NULL;
    char err[256];
    const double inclines[3] = {15, 30, 45};
    double sim_all[3 * SIM_REPS], roll_all[3 * BATCHES], paper_all[3 * BATCHES];
    int n_sim = 0, n_roll = 0, n_paper = 0;
    double worst_dt = 0.0, worst_dx = 0.0;
    printf("jumpcyl %s benchmark: the paper's cylinder, 3.20 m ramp, mu 0.5, single thread\n\n", jc_version());
    printf("incline  full sim median (us)  events  ode steps  rolling predict (us)  paper solve (us)  "
           "first lift-off dt vs tight (s)  dx (m)\n");
    for (int c = 0; c < 3; ++c) {
        jc_Setup s = jc_paper_setup();
        s.incline_rad = inclines[c] * 3.14159265358979323846 / 180.0;
        jc_Model m;
        double t_sim[SIM_REPS];
        jc_Run run;
        time_runs(&s, t_sim, &m, &run);
        const jc_SimOptions o = jc_default_sim_options();
        const int events = run.event_count;
        const long steps = run.ode_steps;
        double t_def, x_def, t_tight, x_tight;
        first_liftoff(&run, &t_def, &x_def);
        jc_run_free(&run);
        jc_SimOptions tight = o;
        tight.ode_rtol *= 1e-2;
        tight.ode_atol *= 1e-2;
        tight.event_tol_s *= 1e-2;
        if (jc_simulate(&m, &tight, &run, err, sizeof err)) die("simulate", err);
        first_liftoff(&run, &t_tight, &x_tight);
        jc_run_free(&run);
        const double dt = fabs(t_def - t_tight), dx = fabs(x_def - x_tight);
        worst_dt = fmax(worst_dt, dt);
        worst_dx = fmax(worst_dx, dx);

        double t_roll[BATCHES], t_paper[BATCHES];
        jc_RollingResult rr;
        jc_PaperResult pr;
        for (int b = 0; b < BATCHES; ++b) {
            double t0 = now_us();
            for (int i = 0; i < BATCH; ++i)
                if (jc_rolling_predict(&m, &rr, err, sizeof err)) die("rolling", err);
            t_roll[b] = (now_us() - t0) / BATCH;
            t0 = now_us();
            for (int i = 0; i < BATCH / 10; ++i)
                if (jc_paper_solve(&m, &pr, err, sizeof err)) die("paper", err);
            t_paper[b] = (now_us() - t0) / (BATCH / 10);
        }
        for (int i = 0; i < SIM_REPS; ++i) sim_all[n_sim++] = t_sim[i];
        for (int b = 0; b < BATCHES; ++b) { roll_all[n_roll++] = t_roll[b]; paper_all[n_paper++] = t_paper[b]; }
        const double ms = median(t_sim, SIM_REPS), mr = median(t_roll, BATCHES), mp = median(t_paper, BATCHES);
        printf("%5.0f deg %21.1f %7d %10ld %21.3f %17.2f %31.1e %7.1e\n", inclines[c], ms, events, steps, mr, mp, dt, dx);
    }
    /* The same runs with air drag on (C_d 0.6): rolling and flight become ODEs. */
    double drag_all[3 * SIM_REPS];
    int n_drag = 0;
    printf("\nwith air drag (C_d 0.6):\nincline  full sim median (us)  events  ode steps\n");
    for (int c = 0; c < 3; ++c) {
        jc_Setup s = jc_paper_setup();
        s.incline_rad = inclines[c] * 3.14159265358979323846 / 180.0;
        s.drag_coefficient = 0.6;
        jc_Model m;
        double t_sim[SIM_REPS];
        jc_Run run;
        time_runs(&s, t_sim, &m, &run);
        for (int i = 0; i < SIM_REPS; ++i) drag_all[n_drag++] = t_sim[i];
        printf("%5.0f deg %21.1f %7d %10ld\n", inclines[c], median(t_sim, SIM_REPS), run.event_count, run.ode_steps);
        jc_run_free(&run);
    }
    const double md = median(drag_all, n_drag);
    const double ms = median(sim_all, n_sim), mr = median(roll_all, n_roll), mp = median(paper_all, n_paper);
    printf("\nall inclines: full simulation %.1f us median (%.0f runs/s), rolling prediction %.3f us median "
           "(%.0f /s), paper model %.2f us\n", ms, 1e6 / ms, mr, 1e6 / mr, mp);
    printf("event accuracy: first lift-off within %.1e s and %.1e m of a run with 100x tighter tolerances\n",
           worst_dt, worst_dx);
    printf("with air drag: full simulation %.1f us median (%.1fx the drag-free run)\n", md, md / ms);
    batch_rates br = {{-1, -1}, {-1, -1}, -1, -1};
    if (cli) time_batch(cli, mpi_cli, &br);
    printf("{\"full_sim_us_median\": %.3f, \"rolling_predict_us_median\": %.4f, \"paper_solve_us_median\": %.3f, "
           "\"full_sim_drag_us_median\": %.3f, \"first_liftoff_dt_s\": %.3e, \"first_liftoff_dx_m\": %.3e",
           ms, mr, mp, md, worst_dt, worst_dx);
    if (cli)
        printf(", \"sweep_sims_per_s_1t\": %.0f, \"sweep_sims_per_s_2t\": %.0f, \"mc_sims_per_s_1t\": %.0f, "
               "\"mc_sims_per_s_2t\": %.0f, \"sweep_sims_per_s_mpi2\": %.0f, \"million_sims_s\": %.2f, "
               "\"mc_samples_per_s\": %.0f",
               br.sweep[0], br.sweep[1], br.mc[0], br.mc[1], br.sweep_mpi, 1e6 / br.sweep[1], br.mc_output);
    /* make bench times jc.simulate from Python first (python/bench_simulate.py). */
    const char *py_us = getenv("JC_BENCH_PYTHON_US");
    if (py_us && *py_us) {
        const double us = atof(py_us);
        printf(", \"python_simulate_us\": %.3f, \"python_over_c\": %.2f", us, us / ms);
    }
    printf("}\n");
    return 0;
}
