/* paper-uncertainty: for each incline of the paper's Table 1, the jump site
 * it printed, the full model's first lift-off with its 95 % band under the
 * inputs' uncertainties (a Monte Carlo that the caller ran and hands over:
 * fig_Data's site_stats), and the measurement with its error bar: one panel
 * per incline. */
#include "figures.h"

#include <math.h>
#include <string.h>

static double nominal_liftoff(const jc_Model *m, double incline_deg)
{
    jc_Setup s = m->setup;
    s.incline_rad = incline_deg * CLI_PI / 180.0;
    jc_Model mi;
    jc_Run run;
    char err[256];
    const jc_SimOptions o = jc_default_sim_options();
    double x = NAN;
    if (jc_model_init(&mi, &s, err, sizeof err) == JC_OK && jc_simulate(&mi, &o, &run, err, sizeof err) == JC_OK) {
        jc_RunSummary sum;
        jc_run_summarize(&run, &sum);
        if (sum.first_liftoff >= 0) x = sum.first_liftoff_state.x_m;
    }
    jc_run_free(&run);
    return x;
}

int fig_uncertainty_prepare(fig_Data *d)
{
    const jc_PaperTableRow *t;
    const int n = jc_paper_table(&t);
    FILE *gp = d->gp;
    fig_block_begin(gp, "sites");
    fprintf(gp, "# jumpcyl plot --what paper-uncertainty. Positions in cm (centre's travel along the incline).\n"
                "# The full model's spread: %d Monte Carlo samples (seed %d) of the paper's tolerances (normal:\n"
                "# r, rod offset 0.05 cm, masses 0.05 g, theta0 3 deg) and of friction 0.3..1.0 and\n"
                "# restitution 0.1..0.6 (uniform: not measured by the paper).\n"
                "# columns: incline_deg printed_cm nominal_cm p2_5_cm p50_cm p97_5_cm measured_cm measured_error_cm\n",
            d->mc_samples, d->mc_seed);
    for (int i = 0; i < d->table_rows && i < n; ++i) {
        const jc_Stats *st = &d->site_stats[i];
        const double nominal = nominal_liftoff(d->model, t[i].incline_deg);
        fprintf(gp, "%g %.6g %.6g %.6g %.6g %.6g %.6g %.6g\n", t[i].incline_deg, t[i].printed_x_m * 100,
                nominal * 100, st->p2_5 * 100, st->p50 * 100, st->p97_5 * 100, t[i].measured_x_m * 100,
                t[i].measured_error_m * 100);
    }
    fig_block_end(gp);
    return EXIT_OK;
}

/* The panels side by side on a 1800 x 900 page (2:1, for a slide), one
 * key for all of them centred below. */
void fig_uncertainty_panels(FILE *gp, const fig_Data *d)
{
    fprintf(gp, "\nset multiplot layout 1,%d title \"The paper's jump sites: printed, the full model with its 95 %% "
                "band\\n(Monte Carlo, %d samples), measured\" font F_TITLE margins 0.08,0.98,0.24,0.8 spacing 0.07,0\n",
            d->table_rows, d->mc_samples);
    for (int i = 0; i < d->table_rows; ++i) {
        fig_panel_begin(gp, "paper-uncertainty");
        fprintf(gp,
                "row = %d\n"
                "stats $sites every ::row::row using 2 nooutput name 'P'\n"
                "stats $sites every ::row::row using 4 nooutput name 'LO'\n"
                "stats $sites every ::row::row using 6 nooutput name 'HI'\n"
                "stats $sites every ::row::row using 7 nooutput name 'M'\n"
                "stats $sites every ::row::row using 8 nooutput name 'E'\n"
                "stats $sites every ::row::row using 1 nooutput name 'A'\n"
                "ymin = P_min < LO_min ? P_min : LO_min\n"
                "ymin = ymin < M_min - E_min ? ymin : M_min - E_min\n"
                "ymax = P_max > HI_max ? P_max : HI_max\n"
                "ymax = ymax > M_max + E_max ? ymax : M_max + E_max\n"
                "pad = 0.15 * (ymax - ymin)\n"
                "set yrange [ymin - pad : ymax + pad]\n"
                "set xrange [0.4 : 3.6]\n"
                "set xtics ('printed' 1, 'model' 2, 'measured' 3)\n"
                "set grid noxtics\n"
                "%s"
                "set title sprintf('%%g° incline', A_min)\n"
                "# One key for the page, centred below the panels (drawn with the first)\n"
                "%s"
                "plot $sites every ::row::row using (1):2 with points pt 5 ps 2.2*PS lc rgb C_INK title 'printed (Table 1)', \\\n"
                "     '' every ::row::row using (2):5:4:6 with yerrorbars pt 7 ps 2.0*PS lw 3 lc rgb C_BLUE title 'full model: median, 95 %% band', \\\n"
                "     '' every ::row::row using (2.18):3 with points pt 12 ps 2.0*PS lw 2 lc rgb C_GREEN title 'nominal run', \\\n"
                "     '' every ::row::row using (3):7:8 with yerrorbars pt 9 ps 2.2*PS lw 3 lc rgb C_RED title 'measured (± error)'\n",
                i, i == 0 ? "set ylabel 'jump site along the incline (cm)'\n" : "",
                i == 0 ? "set key at screen 0.5, 0.02 center bottom vertical maxrows 2 width 2 font F_SMALL\n" : "unset key\n");
    }
    fputs("unset multiplot\n", gp);
}
