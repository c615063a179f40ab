/* Output options, one rule in every command (docs/cli.md, "Output files"):
 * --json FILE, --csv FILE, --output FILE take a file and "-" is standard
 * output; --json alone (followed by another option or by nothing) is
 * --json -. A document written to a file is the very document standard
 * output carries, and the text beside it is the text without it plus one
 * line naming the file. An output that cannot go to standard output (a
 * figure, a film) refuses "-" in one line, and no file or directory named
 * "-" is ever made. A kept gnuplot script's name, as the tool prints it,
 * is safe to give gnuplot. Runs the built tool (argv[1]) in a scratch
 * directory. */
#define _DEFAULT_SOURCE /* realpath */
#define _POSIX_C_SOURCE 200809L
#include "test.h"
#include "cli_run.h"

#include <cjson/cJSON.h>
#include <fcntl.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

static const char *cli_path;
static char scratch[] = "/tmp/jc_output_options_XXXXXX";

static cli_result run(const char *args) { return cli_run_line(cli_path, NULL, args); }

/* Standard output of a run that must succeed quietly; NULL otherwise. */
static char *out_of(const char *args)
{
    cli_result r = run(args);
    char *out = NULL;
    if (r.status != 0 || !r.out || !r.err || r.err[0]) {
        fprintf(stderr, "'jumpcyl %s': status %d, stderr '%s'\n", args, r.status, r.err ? r.err : "?");
    } else {
        out = r.out;
        r.out = NULL;
    }
    cli_result_free(&r);
    return out;
}

/* Whether a and b are the same text; says where they part. */
static int same_text(const char *what, const char *a, const char *b)
{
    if (a && b && strcmp(a, b) == 0) return 1;
    size_t i = 0;
    while (a && b && a[i] && a[i] == b[i]) ++i;
    fprintf(stderr, "%s: the texts differ at byte %zu: '%.40s' against '%.40s'\n", what, i, a ? a + i : "(none)",
            b ? b + i : "(none)");
    return 0;
}

/* The document of "jumpcyl ARGS" with every way of sending it to standard
 * output (ARGS has "%s" where the option goes) and into a file: all the
 * same text, and the file's run prints the text of the run without --json
 * and "JSON written to FILE". drop: a key that differs from run to run
 * (timings), removed before the documents are compared; NULL for none.
 * forms: how many of the ways to standard output are run (1 to 3; a slow
 * command's run with --json FILE is then only held to its document and
 * its last line). */
static int check_json_option(const char *args, const char *drop, int forms)
{
    static const char *const to_stdout[] = {"--json", "--json -", "--json=-"};
    char line[512], *doc[3] = {NULL, NULL, NULL};
    int bad = 0;
    for (int k = 0; k < forms && !bad; ++k) {
        snprintf(line, sizeof line, args, to_stdout[k]);
        doc[k] = out_of(line);
        bad = !doc[k] || (k > 0 && !drop && !same_text(line, doc[k], doc[0]));
    }
    /* into a file, the option before or after the others */
    snprintf(line, sizeof line, args, "--json out.json");
    char *text = bad ? NULL : out_of(line);
    char *file = cli_run_slurp("out.json");
    snprintf(line, sizeof line, args, "");
    char *plain = bad ? NULL : forms > 1 ? out_of(line) : calloc(1, 1);
    const size_t want_len = (plain ? strlen(plain) : 0) + 64;
    char *want = malloc(want_len);
    if (want) snprintf(want, want_len, "%sJSON written to out.json\n", plain ? plain : "");
    /* design's text holds its timing: there the file's line is looked for */
    if (!bad)
        bad = !text || !file || !plain || !want ||
              (drop || forms == 1 ? !strstr(text, "out.json\n") : !same_text(args, text, want));
    free(want);
    if (!bad && drop) {
        cJSON *a = cJSON_Parse(doc[0]), *b = cJSON_Parse(file), *c = cJSON_Parse(doc[forms - 1]);
        bad = !a || !b || !c;
        if (!bad) {
            cJSON_DeleteItemFromObject(a, drop);
            cJSON_DeleteItemFromObject(b, drop);
            cJSON_DeleteItemFromObject(c, drop);
            bad = !cJSON_Compare(a, b, 1) || !cJSON_Compare(a, c, 1);
            if (bad) fprintf(stderr, "%s: the documents differ (%s aside)\n", args, drop);
        }
        cJSON_Delete(a);
        cJSON_Delete(b);
        cJSON_Delete(c);
    } else if (!bad) {
        bad = !same_text(args, file, doc[0]);
    }
    for (int k = 0; k < 3; ++k) free(doc[k]);
    free(text);
    free(file);
    free(plain);
    remove("out.json");
    ENSURE_MSG(!bad, "jumpcyl %s: --json does not follow the rule", args);
    ENSURE_MSG(!cli_file_exists("-"), "jumpcyl %s: a file named '-' was made", args);
    return 0;
}

static int test_json_everywhere(void)
{
    if (check_json_option("predict %s --mu 0.4", NULL, 3)) return 1;
    if (check_json_option("paper %s", NULL, 1)) return 1; /* half a second a run */
    if (check_json_option("simulate %s --preset hoop", NULL, 3)) return 1;
    if (check_json_option("mc --samples 20 --seed 3 --threads 1 --quiet %s", NULL, 3)) return 1;
    if (check_json_option("params %s", NULL, 3)) return 1;
    /* design's document holds its own timing: "seconds" */
    if (check_json_option("design --jump-at 1.2m --free rod-offset --points 50 --threads 1 %s", "seconds", 3)) return 1;
    return 0;
}

/* design and track: "-" was a file's name; now standard output, alone. */
static int test_dash_is_stdout(void)
{
    char line[1024];
    char *a = out_of("design --jump-at 1.2m --free rod-offset --points 50 --threads 1 --json -");
    cJSON *doc = a ? cJSON_Parse(a) : NULL;
    ENSURE_MSG(doc && cJSON_GetObjectItem(doc, "solutions"), "design --json -: standard output is not the document");
    cJSON_Delete(doc);
    free(a);
    ENSURE(!cli_file_exists("-"));
    snprintf(line, sizeof line, "track '%s/tracker/incline.trk' --json -", JC_EXAMPLES_DIR);
    char *t = out_of(line);
    snprintf(line, sizeof line, "track --json t.json '%s/tracker/incline.trk'", JC_EXAMPLES_DIR);
    char *text = out_of(line);
    char *file = cli_run_slurp("t.json");
    ENSURE_MSG(t && text && file && same_text("track --json", t, file), "track --json - and --json FILE differ");
    ENSURE(strstr(text, "JSON written to t.json\n") != NULL);
    free(t);
    free(text);
    free(file);
    remove("t.json");
    /* the CSV on standard output carries itself alone: its header first */
    char *csv = out_of("simulate --sample-dt 0.05 --csv - --preset hoop");
    ENSURE(csv && strncmp(csv, "t_s,", 4) == 0);
    free(csv);
    ENSURE(!cli_file_exists("-"));
    return 0;
}

/* A run refused with exit 2, one line on standard error that holds want,
 * nothing on standard output, and no "-" made. */
static int refused(const char *args, const char *want)
{
    cli_result r = run(args);
    const int ok = r.status == 2 && cli_one_line(r.err) && strstr(r.err, want) && r.out && !r.out[0];
    if (!ok) fprintf(stderr, "'jumpcyl %s': status %d, stderr '%s'\n", args, r.status, r.err ? r.err : "?");
    cli_result_free(&r);
    ENSURE_MSG(ok, "jumpcyl %s is not refused as it should be", args);
    ENSURE_MSG(!cli_file_exists("-"), "jumpcyl %s made a file named '-'", args);
    return 0;
}

static int test_refusals(void)
{
    char line[512];
    static const char *const figures[] = {
        "plot --what gap --output -", "plot --what gap --output=-", "map --x incline=5:60:5 --y mu=0.3:1:0.1 --output -",
        "animate --output -", "design --jump-at 1.2m --free rod-offset --figure -"};
    for (size_t i = 0; i < sizeof figures / sizeof figures[0]; ++i)
        if (refused(figures[i], "cannot go to standard output")) return 1;
    snprintf(line, sizeof line, "compare --track '%s/tracker/incline.trk' --output -", JC_EXAMPLES_DIR);
    if (refused(line, "cannot go to standard output")) return 1;
    if (refused("simulate --json --csv -", "both write to standard output")) return 1;
    if (refused("simulate --json - --csv -", "both write to standard output")) return 1;
    if (refused("mc --samples 5 --json --output -", "both write to standard output")) return 1;
    if (refused("design --jump-at 1.2m --free rod-offset --json - --csv -", "both write to standard output")) return 1;
    snprintf(line, sizeof line, "track '%s/tracker/incline.trk' --csv - --json", JC_EXAMPLES_DIR);
    if (refused(line, "both write to standard output")) return 1;
    if (refused("simulate --json a.json --csv a.json", "name the same file")) return 1;
    if (refused("predict --json --json", "--json given twice")) return 1;
    if (refused("paper --json a.json --json", "--json given twice")) return 1;
    /* a word after --json that starts with '-' is an option, not a FILE */
    if (refused("predict --json -x.json", "unknown option")) return 1;
    ENSURE(!cli_file_exists("a.json"));
    return 0;
}

/* gnuplot run on one file argument, as given (no shell), its output
 * dropped; its exit status, or -1. */
static int gnuplot_load(const char *name)
{
    fflush(NULL);
    const pid_t pid = fork();
    if (pid == 0) {
        const int null = open("/dev/null", O_WRONLY);
        if (null < 0 || dup2(null, 1) < 0 || dup2(null, 2) < 0) _exit(126);
        execlp("gnuplot", "gnuplot", name, (char *)NULL);
        _exit(127);
    }
    int ws = 0;
    return pid > 0 && waitpid(pid, &ws, 0) == pid && WIFEXITED(ws) ? WEXITSTATUS(ws) : -1;
}

/* A figure named so that its kept script's plain name is a gnuplot pipe
 * ("<touch PWNED;.gp"): the name printed on "Script:" loads the script
 * and runs nothing. */
static int test_kept_script_names(void)
{
    static const char *const outputs[] = {"<touch PWNED;.png"};
    for (size_t i = 0; i < sizeof outputs / sizeof outputs[0]; ++i) {
        const char *args[] = {"plot", "--what", "gap", "--output", outputs[i], "--keep-script", NULL};
        cli_result r = cli_run(args);
        char name[256] = "";
        const char *at = r.out ? strstr(r.out, "Script: ") : NULL;
        const char *end = at ? strstr(at, " (its data inside)") : NULL;
        if (end) snprintf(name, sizeof name, "%.*s", (int)(end - at - 8), at + 8);
        const int status = r.status;
        cli_result_free(&r);
        ENSURE_MSG(status == 0 && name[0], "plot --output '%s' --keep-script: status %d, no Script: line", outputs[i],
                   status);
        const int loaded = gnuplot_load(name);
        const int ran = cli_file_exists("PWNED");
        remove("PWNED");
        remove(outputs[i]);
        char gp[64];
        snprintf(gp, sizeof gp, "%.*s.gp", (int)strlen(outputs[i]) - 4, outputs[i]);
        remove(gp);
        remove("f_touch_PWNED_.png"); /* the script's own figure, under a safe name */
        ENSURE_MSG(!ran, "'gnuplot %s', as plot printed it, ran a shell command", name);
        ENSURE_MSG(loaded == 0, "'gnuplot %s' did not render the figure (exit %d)", name, loaded);
    }
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s PATH_TO_JUMPCYL\n", argv[0]);
        return 2;
    }
    char *tool = realpath(argv[1], NULL);
    if (!tool || !mkdtemp(scratch) || chdir(scratch) != 0) {
        fprintf(stderr, "no tool or no scratch directory\n");
        return 2;
    }
    cli_path = cli_run_tool = tool;
    cli_run_wrapper = argv + 2;
    RUN_TEST(test_json_everywhere);
    RUN_TEST(test_dash_is_stdout);
    RUN_TEST(test_refusals);
    RUN_TEST(test_kept_script_names);
    if (chdir("/tmp") == 0) rmdir(scratch); /* fails, and says so in the listing, if anything was left */
    free(tool);
    TEST_MAIN_END();
}
