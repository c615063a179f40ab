/*
 * Flight (physics.md §4): without contact the only force is gravity,
 * g (sin a, -cos a) in the incline frame, and there is no torque about G. So
 * from the state at the start of a flight (a lift-off, or a bounce into
 * flight) the centre of mass follows
 *   x_G(t) = x_G0 + v_Gx0 t + g sin(a) t^2 / 2
 *   y_G(t) = y_G0 + v_Gy0 t - g cos(a) t^2 / 2
 * and th(t) = th0 + w0 t with w constant. The library integrates the motion of
 * the geometric centre C instead, with remainder series (src/flight.c); here
 * every flight sample is compared with the parabola of G computed from the
 * event's state, the rim is checked to stay above the incline on a dense grid
 * (a skipped touchdown root would show up as a negative gap), the touchdown
 * is checked to be on the incline, and the recorded hop height is compared
 * with the largest gap found on the grid.
 */
#include "sim_common.h"

#include <gsl/gsl_errno.h>

/* Positions are O(1 m); the library's terms (v t, g t^2/2, d (w t)^2 with w t
 * up to ~40 rad) are at most ~100 m, so its rounding is below 1e-13 m, and so
 * is that of the parabola here. 1e-11 m leaves two orders for accumulation
 * and is still 1e-11 of the flight's size: any wrong term (a missing
 * d w^2 sin th, a sign) is millimetres. */
#define POS_TOL_M 1e-11
/* Velocities O(1..10 m/s), same argument. */
#define VEL_TOL_MPS 1e-10
/* w is copied, never integrated, in flight: constant to rounding. */
#define OMEGA_REL_TOL 1e-12
/* Grid points per flight for the gap and hop checks. */
#define GRID 20000

typedef struct {
    double t0, th0, w, xg0, yg0, vgx0, vgy0, gs, gc, d, r;
} parabola;

static void parabola_from(const jc_Model *m, const jc_State *s, parabola *p)
{
    p->t0 = s->t_s;
    p->th0 = s->theta_rad;
    p->w = s->omega_radps;
    cm_position(m, s, &p->xg0, &p->yg0);
    cm_velocity(m, s, &p->vgx0, &p->vgy0);
    p->gs = m->setup.gravity_mps2 * sin(m->setup.incline_rad);
    p->gc = m->setup.gravity_mps2 * cos(m->setup.incline_rad);
    p->d = m->body.cm_offset_m;
    p->r = m->body.radius_m;
}

static void parabola_at(const parabola *p, double t, double *xg, double *yg, double *vgx, double *vgy, double *th)
{
    const double tau = t - p->t0;
    *xg = p->xg0 + p->vgx0 * tau + 0.5 * p->gs * tau * tau;
    *yg = p->yg0 + p->vgy0 * tau - 0.5 * p->gc * tau * tau;
    *vgx = p->vgx0 + p->gs * tau;
    *vgy = p->vgy0 - p->gc * tau;
    *th = p->th0 + p->w * tau;
}

/* Height of the rim's lowest point above the incline: y_C - r. */
static double parabola_gap(const parabola *p, double t)
{
    double xg, yg, vx, vy, th;
    parabola_at(p, t, &xg, &yg, &vx, &vy, &th);
    return yg - p->d * cos(th) - p->r;
}

typedef struct {
    int flights, samples;
    double worst_pos, worst_omega_rel;
} flight_stats;

/* Checks every flight of a run against the parabola of its start state. */
static int check_flights(const jc_Model *m, const jc_Run *run, flight_stats *st)
{
    for (int i = 0; i < run->event_count; ++i) {
        const jc_Event *e = &run->events[i];
        if (e->mode_after != JC_MODE_FLIGHT) continue;
        if (e->kind != JC_EVENT_LIFTOFF && e->kind != JC_EVENT_BOUNCE) continue;
        parabola p;
        parabola_from(m, &e->state, &p);
        const int last = i + 1 >= run->event_count;
        const jc_Event *next = last ? NULL : &run->events[i + 1];
        const double t_end = last ? run->final_state.t_s : next->state.t_s;
        st->flights++;

        /* The flight record: its length is the time to the next event. */
        ENSURE_NEAR(e->flight_time_s, t_end - p.t0, 1e-15 * (1.0 + t_end));
        ENSURE_MSG(e->flight_time_s > 0.0, "flight %d has length %g", i, e->flight_time_s);

        for (int k = 0; k < run->sample_count; ++k) {
            const jc_Sample *s = &run->samples[k];
            if (s->state.t_s < p.t0 || s->state.t_s >= t_end) continue;
            ENSURE_MSG(s->mode == JC_MODE_FLIGHT, "sample at t %.17g inside flight %d is %s", s->state.t_s, i,
                       jc_mode_name(s->mode));
            double xg, yg, vgx, vgy, th;
            parabola_at(&p, s->state.t_s, &xg, &yg, &vgx, &vgy, &th);
            double sxg, syg, svx, svy;
            cm_position(m, &s->state, &sxg, &syg);
            cm_velocity(m, &s->state, &svx, &svy);
            ENSURE_NEAR(sxg, xg, POS_TOL_M);
            ENSURE_NEAR(syg, yg, POS_TOL_M);
            ENSURE_NEAR(s->cm_x_m, xg, POS_TOL_M);
            ENSURE_NEAR(s->cm_y_m, yg, POS_TOL_M);
            ENSURE_NEAR(svx, vgx, VEL_TOL_MPS);
            ENSURE_NEAR(svy, vgy, VEL_TOL_MPS);
            ENSURE_REL(s->state.omega_radps, p.w, OMEGA_REL_TOL);
            /* th = th0 + w tau: the same product, rounding only. */
            ENSURE_NEAR(s->state.theta_rad, th, 1e-13 * (1.0 + fabs(th)));
            /* The sample's gap is y_C - r. */
            ENSURE_NEAR(s->gap_m, parabola_gap(&p, s->state.t_s), POS_TOL_M);
            ENSURE_MSG(s->gap_m >= -POS_TOL_M, "negative gap %g in flight at t %.17g", s->gap_m, s->state.t_s);
            st->worst_pos = fmax(st->worst_pos, fmax(fabs(sxg - xg), fabs(syg - yg)));
            st->worst_omega_rel = fmax(st->worst_omega_rel, fabs(s->state.omega_radps - p.w) / fabs(p.w));
            st->samples++;
        }

        /* No skipped touchdown: the rim stays above the incline inside the
         * flight. Near the ends the gap is O(t^2) or O(t^3) small, so the grid
         * allows the rounding of y_G - d cos th - r (~1e-16 of 1 m). */
        const double T = t_end - p.t0;
        double grid_max = -INFINITY;
        for (int k = 1; k < GRID; ++k) {
            const double gap = parabola_gap(&p, p.t0 + T * k / GRID);
            ENSURE_MSG(gap > -1e-14, "flight %d: rim below the incline (gap %g m) at t = %.17g, before the flight's "
                       "end at %.17g", i, gap, p.t0 + T * k / GRID, t_end);
            grid_max = fmax(grid_max, gap);
        }
        grid_max = fmax(grid_max, fmax(parabola_gap(&p, p.t0), parabola_gap(&p, t_end)));
        /* The hop height is the true maximum: at least the grid's, and above it
         * by at most |gap''| (h/2)^2 / 2 with |gap''| <= g + d w^2 between nodes. */
        const double h = T / GRID;
        const double above = 0.5 * (p.gc + p.d * p.w * p.w + 10.0) * 0.25 * h * h;
        ENSURE_MSG(e->hop_height_m >= grid_max - 1e-13 && e->hop_height_m <= grid_max + above + 1e-13,
                   "flight %d: hop %.17g m, grid maximum %.17g m (+%.3g)", i, e->hop_height_m, grid_max, above);

        if (!last && (next->kind == JC_EVENT_TOUCHDOWN || next->kind == JC_EVENT_BOUNCE)) {
            /* Touchdown: the rim is on the incline at the event, to the event
             * tolerance (1e-12 s) times the approach speed (< 10 m/s). */
            ENSURE_NEAR(parabola_gap(&p, t_end), 0.0, 1e-10);
            ENSURE_NEAR(next->state.y_m, p.r, 1e-10);
            /* The landing position recorded at the lift-off. */
            if (e->kind == JC_EVENT_LIFTOFF) ENSURE_NEAR(e->landing_x_m, next->state.x_m, 1e-15);
            /* The impact's own position and angle are those of the parabola. */
            double xg, yg, vgx, vgy, th;
            parabola_at(&p, t_end, &xg, &yg, &vgx, &vgy, &th);
            ENSURE_NEAR(next->state.x_m, xg - p.d * sin(th), POS_TOL_M);
            ENSURE_NEAR(next->state.theta_rad, th, 1e-13 * (1.0 + fabs(th)));
        }
    }
    return 0;
}

static int run_and_check(const jc_Setup *setup, double t_max, flight_stats *st, jc_Run *run)
{
    jc_Model m;
    if (sim_model(&m, setup)) return 1;
    jc_SimOptions o = jc_default_sim_options();
    o.sample_dt_s = 1e-3;
    o.t_max_s = t_max;
    if (sim_run(&m, &o, run)) return 1;
    int bad = check_run_invariants(&o, run) || check_flights(&m, run, st);
    if (bad) jc_run_free(run);
    return bad;
}

/* Hoop (10 g) with a 100 g point mass on the rim, on a floor, CM on top and
 * w0 = 20 rad/s: d w0^2 = 0.0909 * 400 = 36 m/s^2 > g, so the rim is pulled
 * off the floor at t = 0 and the first event is a lift-off at t = 0 from the
 * initial state (x = 0, y = r, v_C = (r w0, 0)). */
static int test_fast_spin_on_floor(void)
{
    const jc_Setup s = hoop_with_mass(0.10, 0.010, 0.100, 20.0);
    jc_Run run;
    flight_stats st = {0};
    if (run_and_check(&s, 2.0, &st, &run)) return 1;
    ENSURE(run.event_count > 0);
    const jc_Event *e = &run.events[0];
    ENSURE_MSG(e->kind == JC_EVENT_LIFTOFF, "first event %s", jc_event_name(e->kind));
    ENSURE(e->state.t_s == 0.0 && e->mode_before == JC_MODE_ROLLING && e->mode_after == JC_MODE_FLIGHT);
    ENSURE(e->state.x_m == 0.0 && e->state.y_m == 0.10 && e->state.omega_radps == 20.0);
    ENSURE_NEAR(e->state.vx_mps, 0.10 * 20.0, 1e-15);
    ENSURE(e->state.vy_mps == 0.0);
    ENSURE_MSG(st.flights >= 1 && st.samples >= 50, "%d flights, %d samples checked", st.flights, st.samples);
    printf("  floor, w0 20: %d flights, %d flight samples, worst |dG| %.2e m, worst |dw|/w %.2e\n", st.flights,
           st.samples, st.worst_pos, st.worst_omega_rel);
    jc_run_free(&run);
    return 0;
}

/* The same body on a 20 degree incline, started at th0 = 0.3 rad with
 * w0 = 25 rad/s: d w0^2 cos th0 = 54 m/s^2 > g cos a = 9.2 m/s^2, a lift-off
 * at t = 0 again, now with gravity along x as well and a tilted start. */
static int test_fast_spin_on_incline(void)
{
    jc_Setup s = hoop_with_mass(0.10, 0.010, 0.100, 25.0);
    s.incline_rad = 20.0 * DEG;
    s.theta0_rad = 0.3;
    jc_Run run;
    flight_stats st = {0};
    if (run_and_check(&s, 2.0, &st, &run)) return 1;
    ENSURE(run.event_count > 0 && run.events[0].kind == JC_EVENT_LIFTOFF && run.events[0].state.t_s == 0.0);
    ENSURE_MSG(st.flights >= 1 && st.samples >= 50, "%d flights, %d samples checked", st.flights, st.samples);
    printf("  20 deg, w0 25: %d flights, %d flight samples, worst |dG| %.2e m\n", st.flights, st.samples,
           st.worst_pos);
    jc_run_free(&run);
    return 0;
}

/* The paper's cylinder at 30 and 45 degrees: flights that start from a
 * lift-off while sliding (N -> 0) and continue after bounces. */
static int test_paper_flights(void)
{
    const double inclines[] = {30.0, 45.0};
    for (int i = 0; i < 2; ++i) {
        const jc_Setup s = paper_at(inclines[i], 0.5);
        jc_Run run;
        flight_stats st = {0};
        if (run_and_check(&s, 60.0, &st, &run)) return 1;
        ENSURE_MSG(count_events(&run, JC_EVENT_LIFTOFF) >= 1, "no lift-off at %g deg", inclines[i]);
        ENSURE_MSG(st.flights >= 2 && st.samples >= 100, "%d flights, %d samples checked", st.flights, st.samples);
        printf("  paper %g deg: %d flights, %d flight samples, worst |dG| %.2e m\n", inclines[i], st.flights,
               st.samples, st.worst_pos);
        jc_run_free(&run);
    }
    return 0;
}

int main(void)
{
    gsl_set_error_handler_off();
    RUN_TEST(test_fast_spin_on_floor);
    RUN_TEST(test_fast_spin_on_incline);
    RUN_TEST(test_paper_flights);
    TEST_MAIN_END();
}
