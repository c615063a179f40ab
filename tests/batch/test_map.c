/* jumpcyl map end to end (argv[1] is the built tool): a small map renders a
 * whole figure in each format; --keep-script keeps a script that renders it
 * again and a CSV that is, byte for byte, the file `jumpcyl sweep --vary Y
 * --vary X` writes (header included: the map's case i is the sweep's case i,
 * x varying fastest); the map's data block says of every cell what the CSV
 * row says; the paper's setups are marked where they fall inside; bad axes
 * are refused with one line, exit 2 and no file. */
#include "../figures/fig_common.h"


static const char *cli;
static char dir[1024];

/* The small map of most tests: 5 inclines x 4 rod offsets. */
#define X_AXIS "incline=10:50:10"
#define Y_AXIS "rod-offset=2cm:8cm:2cm"
#define NX 5
#define NY 4

/* The tool run with args: exit 0, and standard output holding say and also
 * where they are not NULL. */
static int run_says(const char *args, const char *say, const char *also)
{
    cli_result r = cli_run_line(cli, NULL, args);
    const int ok = r.status == 0 && (!say || (r.out && strstr(r.out, say))) && (!also || (r.out && strstr(r.out, also)));
    if (!ok)
        fprintf(stderr, "'%s': status %d, stdout: %s, stderr: %s\n", args, r.status, r.out ? r.out : "?",
                r.err ? r.err : "?");
    cli_result_free(&r);
    return ok;
}

static int run_ok(const char *args) { return run_says(args, NULL, NULL); }

/* A PNG of w x h that ends with its IEND chunk. */
static int whole_png(const char *path, int w, int h)
{
    int pw, ph;
    if (fig_png_size(path, &pw, &ph) != 0 || pw != w || ph != h) return 0;
    char *data = cli_run_slurp(path);
    const long size = fig_file_size(path);
    const int ok = data && size > 12 && memcmp(data + size - 8, "IEND", 4) == 0;
    free(data);
    return ok;
}

/* Whether the file's last bytes, trailing white space aside, are end (a
 * PDF is binary: read as bytes). */
static int ends_with(const char *path, const char *end)
{
    FILE *f = fopen(path, "rb");
    if (!f) return 0;
    char tail[64];
    const long size = fig_file_size(path);
    const long from = size > (long)sizeof tail ? size - (long)sizeof tail : 0;
    size_t n = fseek(f, from, SEEK_SET) == 0 ? fread(tail, 1, sizeof tail, f) : 0;
    fclose(f);
    while (n > 0 && (tail[n - 1] == '\n' || tail[n - 1] == '\r' || tail[n - 1] == ' ')) --n;
    const size_t m = strlen(end);
    return n >= m && memcmp(tail + n - m, end, m) == 0;
}

/* Neither the script nor the rows (stem.gp, stem.csv) that --keep-script keeps are in dir. */
static int no_script_or_rows(const char *stem)
{
    static const char *const kept[] = {"gp", "csv"};
    for (int i = 0; i < 2; ++i) {
        char path[1100];
        snprintf(path, sizeof path, "%s/%s.%s", dir, stem, kept[i]);
        ENSURE_MSG(!cli_file_exists(path), "%s was written", path);
    }
    return 0;
}

static int test_small_map_png(void)
{
    char out[1100], args[2400];
    snprintf(out, sizeof out, "%s/small.png", dir);
    snprintf(args, sizeof args, "map --x " X_AXIS " --y " Y_AXIS " --output '%s'", out);
    ENSURE(run_says(args, "Map: 20 cases (5 x 4)", "Figure: "));
    ENSURE(whole_png(out, 1200, 750));
    /* Without --keep-script: the figure alone. */
    return no_script_or_rows("small");
}

static int test_svg_and_pdf(void)
{
    char out[1100], args[2400];
    snprintf(out, sizeof out, "%s/small.svg", dir);
    snprintf(args, sizeof args, "map --x " X_AXIS " --y " Y_AXIS " --output '%s' --quiet", out);
    ENSURE(run_ok(args));
    ENSURE(ends_with(out, "</svg>"));
    snprintf(out, sizeof out, "%s/small.pdf", dir);
    snprintf(args, sizeof args, "map --x " X_AXIS " --y " Y_AXIS " --output '%s' --quiet", out);
    ENSURE(run_ok(args));
    ENSURE(ends_with(out, "%%EOF"));
    return 0;
}

/* The kept rows are the sweep's file: same header, same rows, same bytes. */
static int test_kept_csv_is_the_sweep(void)
{
    char out[1100], csv[1100], gp[1100], sweep[1100], args[2400];
    snprintf(out, sizeof out, "%s/kept.png", dir);
    snprintf(csv, sizeof csv, "%s/kept.csv", dir);
    snprintf(gp, sizeof gp, "%s/kept.gp", dir);
    snprintf(sweep, sizeof sweep, "%s/sweep.csv", dir);
    snprintf(args, sizeof args, "map --x " X_AXIS " --y " Y_AXIS " --output '%s' --keep-script --threads 2", out);
    ENSURE(run_says(args, "Script: ", "Rows: "));
    ENSURE(whole_png(out, 1200, 750));
    ENSURE(cli_file_exists(gp));
    snprintf(args, sizeof args, "sweep --vary " Y_AXIS " --vary " X_AXIS " --output '%s' --threads 1", sweep);
    ENSURE(run_ok(args));
    char *a = cli_run_slurp(csv), *b = cli_run_slurp(sweep);
    ENSURE(a && b);
    const int same = strcmp(a, b) == 0;
    if (!same) fprintf(stderr, "map's rows:\n%s\nsweep's rows:\n%s\n", a, b);
    int lines = 0;
    for (const char *c = a; *c; ++c) lines += *c == '\n';
    const int header_ok = strncmp(a, "case,rod_offset_m,incline_deg,first_event,", 42) == 0;
    free(a);
    free(b);
    ENSURE(same);
    ENSURE_MSG(lines == 1 + NX * NY, "%d lines", lines);
    ENSURE(header_ok);
    return 0;
}

/* The n-th comma-separated field of a CSV line into out ("" when empty). */
static void csv_field(const char *line, int n, char *out, size_t len)
{
    for (int i = 0; i < n && line; ++i) {
        line = strchr(line, ',');
        if (line) ++line;
    }
    size_t k = 0;
    while (line && line[k] && line[k] != ',' && line[k] != '\n' && k + 1 < len) {
        out[k] = line[k];
        ++k;
    }
    out[k] = '\0';
}

/* The kind a CSV row describes, as the map's data block numbers it. */
static int row_kind(const char *row)
{
    char first[32], slip_x[64], lift_x[64], term[32];
    /* case, rod_offset_m, incline_deg, then the outcome columns */
    csv_field(row, 3, first, sizeof first);
    csv_field(row, 5, slip_x, sizeof slip_x);
    csv_field(row, 8, lift_x, sizeof lift_x);
    csv_field(row, 13, term, sizeof term);
    if (strcmp(term, "invalid_setup") == 0) return 3;
    if (strcmp(term, "failed") == 0) return 4;
    if (strcmp(first, "slip") == 0 && strtod(slip_x, NULL) <= 1e-9) return 2;
    return *lift_x ? 0 : 1;
}

/* The rows of a data block "$name << EOD" ... "EOD" (comments and blank
 * lines skipped), each up to max numbers; the row count, -1 if none. */
static int read_block(const char *script, const char *name, double rows[][6], int cap)
{
    char head[64];
    snprintf(head, sizeof head, "$%s << EOD\n", name);
    const char *p = strstr(script, head);
    if (!p) return -1;
    p += strlen(head);
    int n = 0;
    while (*p && strncmp(p, "EOD\n", 4) != 0) {
        const char *nl = strchr(p, '\n');
        if (!nl) return -1;
        if (*p != '#' && *p != '\n' && n < cap) {
            char *end;
            const char *s = p;
            for (int k = 0; k < 6; ++k) {
                rows[n][k] = strtod(s, &end);
                if (end == s) rows[n][k] = NAN;
                s = end;
            }
            ++n;
        }
        p = nl + 1;
    }
    return n;
}

/* The data block holds, for every cell, what its CSV row says. */
static int test_data_block_matches_rows(void)
{
    char gp[1100], csv[1100];
    snprintf(gp, sizeof gp, "%s/kept.gp", dir);
    snprintf(csv, sizeof csv, "%s/kept.csv", dir);
    char *script = cli_run_slurp(gp), *rows = cli_run_slurp(csv);
    ENSURE(script && rows);
    double cells[NX * NY + 1][6];
    const int n = read_block(script, "map", cells, NX * NY + 1);
    int bad = n != NX * NY;
    if (bad) fprintf(stderr, "%d cells in $map\n", n);
    const char *row = strchr(rows, '\n') + 1; /* after the header */
    for (int i = 0; !bad && i < n; ++i, row = strchr(row, '\n') + 1) {
        char f[64];
        const double *c = cells[i];
        csv_field(row, 0, f, sizeof f);
        bad |= strtol(f, NULL, 10) != i || c[4] != i % NX || c[5] != i / NX;
        csv_field(row, 2, f, sizeof f); /* incline_deg: x */
        bad |= fabs(c[0] - strtod(f, NULL)) > 1e-9;
        csv_field(row, 1, f, sizeof f); /* rod_offset_m: y in cm */
        bad |= fabs(c[1] - 100 * strtod(f, NULL)) > 1e-9;
        const int kind = row_kind(row);
        bad |= (int)c[3] != kind;
        csv_field(row, 8, f, sizeof f); /* first_liftoff_x_m */
        if (kind == 0) bad |= !(fabs(c[2] - 100 * strtod(f, NULL)) <= 1e-8 * fabs(c[2]));
        else bad |= !isnan(c[2]);
        if (bad) fprintf(stderr, "cell %d: %g %g %g %g, row: %.*s\n", i, c[0], c[1], c[2], c[3],
                         (int)(strchr(row, '\n') - row), row);
    }
    /* The three paper setups (15, 30, 45 deg at the preset's 5.5 cm) lie inside. */
    double paper[4][6];
    const int np = read_block(script, "paper", paper, 4);
    const int paper_ok = np == 3 && paper[0][0] == 15 && paper[1][0] == 30 && paper[2][0] == 45 &&
                         fabs(paper[0][1] - 5.5) < 1e-9 && strstr(script, "'paper 45°'") &&
                         strstr(script, "title 'the paper''s setups'");
    free(script);
    free(rows);
    ENSURE(!bad);
    ENSURE_MSG(paper_ok, "%d paper points", np);
    return 0;
}

static int test_kept_script_reruns(void)
{
    char out[1100], cmd[2400];
    snprintf(out, sizeof out, "%s/kept.png", dir);
    ENSURE(remove(out) == 0);
    snprintf(cmd, sizeof cmd, "cd '%s' && gnuplot kept.gp 2>/dev/null", dir);
    ENSURE(system(cmd) == 0);
    ENSURE(whole_png(out, 1200, 750));
    return 0;
}

/* Only the paper's setups inside the ranges are marked; none without incline 15-45 in view. */
static int test_paper_points_in_range(void)
{
    char out[1100], gp[1100], args[2400];
    snprintf(out, sizeof out, "%s/narrow.png", dir);
    snprintf(gp, sizeof gp, "%s/narrow.gp", dir);
    snprintf(args, sizeof args, "map --x incline=20:40:5 --y " Y_AXIS " --output '%s' --keep-script --quiet", out);
    ENSURE(run_ok(args));
    char *script = cli_run_slurp(gp);
    ENSURE(script);
    double paper[4][6];
    const int np = read_block(script, "paper", paper, 4);
    const int one = np == 1 && paper[0][0] == 30 && strstr(script, "'paper 30°'") && !strstr(script, "'paper 15°'");
    free(script);
    ENSURE_MSG(one, "%d paper points", np);
    /* Neither axis is the incline: one point at the preset's values; another
     * restitution makes it the paper's values only. */
    snprintf(args, sizeof args,
             "map --x rod-mass=20g:40g:5g --y " Y_AXIS " --restitution 0.6 --output '%s' --keep-script --quiet", out);
    ENSURE(run_ok(args));
    script = cli_run_slurp(gp);
    ENSURE(script);
    const int all = read_block(script, "paper", paper, 4) == 1 && fabs(paper[0][0] - 32.1) < 1e-9 &&
                    strstr(script, "'paper (all inclines)'") && strstr(script, "its other values differ");
    free(script);
    ENSURE(all);
    snprintf(args, sizeof args, "map --x incline=50:60:5 --y " Y_AXIS " --output '%s' --keep-script --quiet", out);
    ENSURE(run_ok(args));
    script = cli_run_slurp(gp);
    ENSURE(script);
    const int none = read_block(script, "paper", paper, 4) == -1 && !strstr(script, "set label");
    free(script);
    ENSURE(none);
    return 0;
}

/* Cells that slide from the start and setups that are not valid have their
 * own kinds and key entries; an uneven list is drawn as boxes. */
static int test_categories(void)
{
    char out[1100], gp[1100], args[2400];
    snprintf(out, sizeof out, "%s/cat.png", dir);
    snprintf(gp, sizeof gp, "%s/cat.gp", dir);
    snprintf(args, sizeof args, "map --x incline=30:60:10 --y mu=0.05:0.3:0.05 --output '%s' --keep-script --quiet",
             out);
    ENSURE(run_ok(args));
    ENSURE(whole_png(out, 1200, 750));
    char *script = cli_run_slurp(gp);
    ENSURE(script);
    double cells[32][6];
    int n = read_block(script, "map", cells, 32), slides = 0;
    for (int i = 0; i < n; ++i) slides += cells[i][3] == 2;
    const int slides_ok = n == 24 && slides > 0 && strstr(script, "slides from the start (") && strstr(script, "with image");
    free(script);
    ENSURE_MSG(slides_ok, "%d cells, %d slide from the start", n, slides);

    /* A rod 8 cm out does not fit in a 6 cm rim: those cells are not valid setups. */
    snprintf(args, sizeof args,
             "map --x radius=6cm:10cm:2cm --y rod-offset=2cm:8cm:3cm --output '%s' --keep-script --quiet", out);
    cli_result r = cli_run_line(cli, NULL, args);
    ENSURE_MSG(r.status == 0, "status %d: %s", r.status, r.err ? r.err : "?");
    ENSURE(r.err && strstr(r.err, "not valid setups") && !strstr(r.err, "their rows"));
    cli_result_free(&r);
    script = cli_run_slurp(gp);
    ENSURE(script);
    int invalid = 0;
    n = read_block(script, "map", cells, 32);
    for (int i = 0; i < n; ++i) invalid += cells[i][3] == 3;
    const int invalid_ok = n == 9 && invalid > 0 && strstr(script, "not a valid setup (");
    free(script);
    ENSURE_MSG(invalid_ok, "%d cells, %d invalid", n, invalid);

    snprintf(args, sizeof args, "map --x incline=10,20,45 --y mu=0.2,0.3,0.6 --output '%s' --keep-script --quiet", out);
    ENSURE(run_ok(args));
    ENSURE(whole_png(out, 1200, 750));
    script = cli_run_slurp(gp);
    ENSURE(script);
    const int boxes = strstr(script, "array X_EDGES[4] = [5, 15, 32.5, 57.5]") && strstr(script, "with boxxyerror") &&
                      !strstr(script, "with image");
    free(script);
    ENSURE(boxes);
    return 0;
}

/* Exit 2, one line naming the value, and no file at all. */
static int refused(const char *axes, const char *needle)
{
    char out[1100], args[2400];
    snprintf(out, sizeof out, "%s/bad.png", dir);
    snprintf(args, sizeof args, "map %s --output '%s' --keep-script", axes, out);
    cli_result r = cli_run_line(cli, NULL, args);
    const int ok = r.status == 2 && cli_one_line(r.err) && strstr(r.err, needle) && r.out && !*r.out;
    if (!ok) fprintf(stderr, "'%s': status %d, stderr: %s", args, r.status, r.err ? r.err : "?\n");
    cli_result_free(&r);
    ENSURE(ok);
    ENSURE_MSG(!cli_file_exists(out), "%s was written", out);
    return no_script_or_rows("bad");
}

static int test_bad_axes(void)
{
    static const struct {
        const char *axes, *needle;
    } cases[] = {
        {"--x incline=5:5:1 --y mu=0.1:0.5:0.1", "'incline=5:5:1': 1 value (allowed: at least 2"},
        {"--x incline=10:20:5 --y mu=0.3,0.3", "--y 'mu=0.3,0.3': the values must increase"},
        {"--x incline=10,30,20 --y mu=0.1:0.5:0.1", "--x 'incline=10,30,20': the values must increase"},
        {"--x incline=5:95:1 --y mu=0.1:0.5:0.1", "--x 'incline=5:95:1': the value 90 deg is not allowed"},
        {"--x incline=10:20:abc --y mu=0.1:0.5:0.1", "--x 'incline=10:20:abc'"},
        {"--x incline=10:20:5 --y mu=-1,0.5", "--y 'mu=-1,0.5': the value -1 is not allowed"},
        {"--x bogus=1:2:1 --y mu=0.1:0.5:0.1", "'bogus' is not a single-valued setup option"},
        {"--x incline=0:60:0.01 --y rod-offset=1cm:9cm:0.001cm", "6001 values and --y 'rod-offset=1cm:9cm:0.001cm' 8001"},
        {"--x incline=0:60:0.01 --y rod-offset=1cm:9cm:0.001cm", "(allowed: at most 1000000"},
        {"--x incline=10:20:5 --y incline=30:40:5", "--x and --y both vary incline"},
        {"--incline 30 --x incline=10:20:5 --y mu=0.1:0.5:0.1", "--incline and --x incline both given"},
        {"--mu 0.4 --x incline=10:20:5 --y mu=0.1:0.5:0.1", "--mu and --y mu both given"},
        {"--x impact-law=stronge,newton --y mu=0.1:0.5:0.1", "impact-law is a name, not a number"},
        {"--x incline=10:20:5", "--x NAME=VALUES and --y NAME=VALUES are required"},
        {"--x incline=10:20:5 --y mu=0.1:0.5:0.1 --threads 0", "--threads '0'"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i)
        if (refused(cases[i].axes, cases[i].needle)) return 1;
    /* The output's extension, before any work. */
    char args[2400], out[1100];
    snprintf(out, sizeof out, "%s/bad.jpg", dir);
    snprintf(args, sizeof args, "map --x " X_AXIS " --y " Y_AXIS " --output '%s'", out);
    cli_result r = cli_run_line(cli, NULL, args);
    const int ok = r.status == 2 && cli_one_line(r.err) && strstr(r.err, "unknown format '.jpg'");
    cli_result_free(&r);
    ENSURE(ok);
    ENSURE(!cli_file_exists(out));
    /* A directory that does not exist: exit 1 naming it, before any work. */
    snprintf(out, sizeof out, "%s/no/such/dir/m.png", dir);
    snprintf(args, sizeof args, "map --x " X_AXIS " --y " Y_AXIS " --output '%s'", out);
    r = cli_run_line(cli, NULL, args);
    const int dir_ok = r.status == 1 && cli_one_line(r.err) && strstr(r.err, "no/such/dir") && r.out && !*r.out;
    cli_result_free(&r);
    ENSURE(dir_ok);
    return 0;
}

static int test_missing_gnuplot(void)
{
    char out[1100], args[2400];
    snprintf(out, sizeof out, "%s/nognuplot.png", dir);
    snprintf(args, sizeof args, "map --x " X_AXIS " --y " Y_AXIS " --output '%s' --keep-script", out);
    if (fig_without_tools(cli, dir, args, out, "gnuplot was not found", NULL, 1)) return 1;
    snprintf(out, sizeof out, "%s/nognuplot.csv", dir);
    ENSURE(!cli_file_exists(out));
    return 0;
}

/* Nothing but the figure, its script and its rows is left in the directory. */
static int test_no_leftovers(void)
{
    char sub[1100], args[2400], out[1200];
    snprintf(sub, sizeof sub, "%s/clean", dir);
    ENSURE(mkdir(sub, 0755) == 0);
    snprintf(out, sizeof out, "%s/m.png", sub);
    snprintf(args, sizeof args, "map --x " X_AXIS " --y " Y_AXIS " --output '%s' --quiet", out);
    ENSURE(run_ok(args));
    ENSURE_MSG(fig_count_entries(sub) == 1, "%d files", fig_count_entries(sub));
    snprintf(args, sizeof args, "map --x " X_AXIS " --y " Y_AXIS " --output '%s' --quiet --keep-script", out);
    ENSURE(run_ok(args));
    ENSURE_MSG(fig_count_entries(sub) == 3, "%d files (png, gp, csv)", fig_count_entries(sub));
    return 0;
}

int main(int argc, char **argv)
{
    const int rc = fig_main_begin(argc, argv, "map", &cli, dir, sizeof dir);
    if (rc != 0) return rc;
    RUN_TEST(test_small_map_png);
    RUN_TEST(test_svg_and_pdf);
    RUN_TEST(test_kept_csv_is_the_sweep);
    RUN_TEST(test_data_block_matches_rows);
    RUN_TEST(test_kept_script_reruns);
    RUN_TEST(test_paper_points_in_range);
    RUN_TEST(test_categories);
    RUN_TEST(test_bad_axes);
    RUN_TEST(test_missing_gnuplot);
    RUN_TEST(test_no_leftovers);
    fig_main_end(dir);
    TEST_MAIN_END();
}
