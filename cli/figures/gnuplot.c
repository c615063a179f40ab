/* gnuplot scripts: the terminal for each output format, the one style block
 * every jumpcyl figure shares, and running gnuplot so that the figure file is
 * written whole or not at all. */
#define _POSIX_C_SOURCE 200809L
#include "figures.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

/* A panel is designed on a 1200 x 750 pixel canvas with an 18 pt font:
 * legible when projected. The three terminals size text, lines and points
 * differently; these factors (measured by rendering the same test page in
 * each) make the PNG, the SVG and the 10 in wide PDF look alike. */
#define PANEL_W_PX 1200
#define PANEL_H_PX 750
#define PDF_INCH_PER_PX (10.0 / 1200.0)

typedef struct {
    double font, small, title; /* text sizes: base, labels in graphs, titles */
    double linewidth;          /* terminal line width multiplier */
    double pointscale;         /* multiplier for every point size (PS) */
} fig_TermScale;

static const fig_TermScale term_scale[] = {
    [FIG_PNG] = {18.0, 15.0, 20.0, 1.5, 1.0},
    [FIG_SVG] = {22.0, 18.0, 24.5, 1.5, 0.4},
    [FIG_PDF] = {10.8, 9.0, 12.0, 1.5, 0.7},
};

int fig_format_from_path(const char *path, fig_Format *f)
{
    const char *ext = cli_path_ext(path);
    if (strcasecmp(ext, "png") == 0) *f = FIG_PNG;
    else if (strcasecmp(ext, "svg") == 0) *f = FIG_SVG;
    else if (strcasecmp(ext, "pdf") == 0) *f = FIG_PDF;
    else return -1;
    return 0;
}

void fig_quote(FILE *gp, const char *s)
{
    /* In a single-quoted gnuplot string only the quote itself is special. */
    fputc('\'', gp);
    for (; *s; ++s) {
        if (*s == '\'') fputc('\'', gp);
        fputc(*s == '\n' ? ' ' : *s, gp);
    }
    fputc('\'', gp);
}

void fig_block_begin(FILE *gp, const char *name) { fprintf(gp, "$%s << EOD\n", name); }

void fig_block_end(FILE *gp) { fputs("EOD\n", gp); }

static void write_terminal(FILE *gp, fig_Format f, double cols, double rows)
{
    const fig_TermScale *k = &term_scale[f];
    const int w = (int)lround(PANEL_W_PX * cols), h = (int)lround(PANEL_H_PX * rows);
    if (f == FIG_PNG) fprintf(gp, "set terminal pngcairo size %d,%d", w, h);
    else if (f == FIG_SVG) fprintf(gp, "set terminal svg size %d,%d dynamic", w, h);
    else fprintf(gp, "set terminal pdfcairo size %gin,%gin fontscale 1", w * PDF_INCH_PER_PX, h * PDF_INCH_PER_PX);
    fprintf(gp, " enhanced font 'Sans,%g' linewidth %g background rgb 'white'\n", k->font, k->linewidth);
    fprintf(gp, "F_SMALL = ',%g'   # labels inside graphs and keys\nF_TITLE = ',%g'   # titles\n"
                "PS = %g           # point sizes are multiples of this (terminals differ)\n",
            k->small, k->title, k->pointscale);
}

/* Colour-blind-safe colours (Okabe and Ito), one meaning each across figures. */
static const char *const style_colours =
    "# Colours (Okabe-Ito palette, colour-blind safe); one meaning each in every figure.\n"
    "C_BLUE   = '#0072B2'   # speed, kinetic side, normal force\n"
    "C_RED    = '#D55E00'   # thresholds, friction, gap\n"
    "C_GREEN  = '#009E73'   # exact model markers, potential energy\n"
    "C_ORANGE = '#E69F00'   # friction losses\n"
    "C_PURPLE = '#CC79A7'   # impact losses\n"
    "C_GREY   = '#777777'   # events and references\n"
    "C_INK    = '#222222'   # text, markers, sums\n"
    "LW = 2.5               # width of data curves\n";

/* Applied at the start of every panel (after `reset`), so that all kinds of
 * figure and the four panels of the overview look alike. */
static const char *const style_block =
    "$STYLE << EOS\n"
    "set encoding utf8\n"
    "set border 3 lw 1.2 lc rgb C_INK\n"
    "set tics nomirror out scale 0.7 textcolor rgb C_INK\n"
    "set grid xtics ytics lw 0.8 lc rgb '#dddddd' dt 1\n"
    "set key below left Left reverse vertical maxrows 4 samplen 2.5 spacing 1.1 font F_SMALL noautotitle textcolor rgb C_INK\n"
    "set style textbox opaque noborder margins 2,1\n"
    "set style fill transparent solid 0.18 noborder\n"
    "set minussign\n"
    "set format x '%g'\n"
    "set format y '%g'\n"
    "set format y2 '%g'\n"
    "set title font F_TITLE\n"
    "EOS\n";

void fig_script_begin(FILE *gp, fig_Format f, double cols, double rows, const char *default_output,
                      const char *command_line)
{
    fprintf(gp, "# Made by jumpcyl %s:\n#   %s\n", jc_version(), command_line);
    fputs("# To restyle, edit this file and run it again from its directory:\n"
          "#   gnuplot THIS.gp                             (writes the file named below)\n"
          "#   gnuplot -e \"outfile='other.png'\" THIS.gp    (another name, same format)\n"
          "# It reads no file: the data are the data blocks ($run << EOD ... EOD) below, whose\n"
          "# first lines say what each column is.\n\n",
          gp);
    fputs("if (!exists(\"outfile\")) outfile = ", gp);
    fig_quote(gp, default_output);
    fputc('\n', gp);
    write_terminal(gp, f, cols, rows);
    fputs("set output outfile\nset encoding utf8\n\n", gp);
    fputs(style_colours, gp);
    fputs("\n# ---- The style every panel applies: edit here to restyle all of them ----\n", gp);
    fputs(style_block, gp);
    fputs("STYLE_LINES = |$STYLE|\n", gp);
}

void fig_panel_begin(FILE *gp, const char *what)
{
    fprintf(gp, "\n# ================= panel: %s =================\n", what);
    fputs("reset\ndo for [i = 1:STYLE_LINES] { eval $STYLE[i] }\n", gp);
}

void fig_command_line(int argc, char **argv, char *out, size_t len)
{
    char *buf = NULL;
    size_t n = 0;
    FILE *m = open_memstream(&buf, &n);
    if (!m) {
        snprintf(out, len, "jumpcyl %s", argc > 0 ? argv[0] : "");
        return;
    }
    fputs("jumpcyl", m);
    for (int i = 0; i < argc; ++i) {
        fputc(' ', m);
        cli_shell_word(m, argv[i]);
    }
    fclose(m);
    snprintf(out, len, "%s", buf ? buf : "jumpcyl");
    free(buf);
}

void fig_caption(const jc_Model *m, char *out, size_t len)
{
    const jc_Setup *s = &m->setup;
    snprintf(out, len, "%.4g° incline, μ_s = %.3g, μ_k = %.3g, e = %.3g%s", cli_deg(s->incline_rad), s->mu_static,
             s->mu_kinetic, s->restitution, jc_setup_has_resistance(s) ? ", air/rolling resistance" : "");
}

void fig_body_caption(const jc_Model *m, char *out, size_t len)
{
    snprintf(out, len, "r = %.3g cm, d = %.3g cm (paper's model: %.3g cm), M = %.4g g", m->body.radius_m * 100,
             m->body.cm_offset_m * 100, m->paper_d_m * 100, m->body.mass_kg * 1e3);
}

const char *fig_scratch_name(fig_Format f)
{
    return f == FIG_PNG ? "figure.png" : f == FIG_SVG ? "figure.svg" : "figure.pdf";
}

cli_Check fig_check(fig_Format f)
{
    return f == FIG_PNG ? CLI_CHECK_PNG : f == FIG_SVG ? CLI_CHECK_SVG : CLI_CHECK_PDF;
}

int fig_render(const char *cmd, const char *work, fig_Format f, const char *output)
{
    char log_path[CLI_PATH_MAX], figure[CLI_PATH_MAX], pre[64], label[64];
    if (cli_path_join(log_path, sizeof log_path, work, FIG_LOG_NAME) != 0 ||
        cli_path_join(figure, sizeof figure, work, fig_scratch_name(f)) != 0) {
        cli_error("%s: scratch path too long: %s", cmd, work);
        return EXIT_FAIL;
    }
    /* Run in the scratch directory on names made here: nothing the user
     * typed is in gnuplot's arguments or in the script it reads. */
    snprintf(pre, sizeof pre, "outfile = '%s'", fig_scratch_name(f));
    char *argv[] = {"gnuplot", "-e", pre, FIG_SCRIPT_NAME, NULL};
    cli_Progress progress;
    snprintf(label, sizeof label, "%s: gnuplot is rendering", cmd);
    cli_progress_begin(&progress, label);
    int status;
    const cli_RunEnd end = cli_run_program(argv, work, log_path, cli_progress_tick, &progress, &status);
    cli_progress_end(&progress);
    if (end == CLI_RUN_STOPPED) return cli_stop_status();
    if (end == CLI_RUN_EFBIG) {
        cli_error("cannot write %s: %s (gnuplot's scratch copy in %s)", output, strerror(EFBIG), work);
        return EXIT_FAIL;
    }
    if (end == CLI_RUN_FAILED) return EXIT_FAIL;
    if (status != 0) {
        cli_error("%s: gnuplot failed (exit status %d) making %s:", cmd, status, output);
        cli_print_log_tail(log_path);
        return EXIT_FAIL;
    }
    /* gnuplot exits 0 after a failed write (a full disk): the file itself
     * must be whole. */
    char why[128];
    if (cli_output_verify(figure, fig_check(f), why, sizeof why) != 0) {
        cli_error("cannot write %s: gnuplot's figure is %s (is %s full?)", output, why, work);
        cli_print_log_tail(log_path);
        return EXIT_FAIL;
    }
    return EXIT_OK;
}
