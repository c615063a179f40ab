/* Fuzz target: the reader of FILE.part (cli_part_read, --resume). The
 * input is a whole .part file, read against a fixed job (a sweep of the
 * incline over 10, 20, 30 deg on the default setup: its job line, header
 * and hash).
 *
 * Invariants: the reader answers 0 (this job's rows), 1 (nothing of value:
 * empty, or the job line cut short) or -1 with a message; 1 only for an
 * input that is a prefix of the job line; with 0, at most the job's cases
 * are taken, the kept bytes end on a whole line within the input, and
 * reading those bytes alone gives the same rows (what --resume keeps is
 * itself a good file); a -1 leaves a message. */
#define _POSIX_C_SOURCE 200809L
#include "fuzz.h"

#include "batch.h"

#include <string.h>

static jc_StudyDef def;
static cli_Param param;
static char header[2 * JC_STUDY_ROW_MAX];
static char job_line[256];
static uint64_t job;

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    static cli_SetupArgs args;
    static cli_SetupValues values;
    jc_Setup base;
    char err[600];
    memset(&args, 0, sizeof args);
    if (cli_param_parse_vary("incline=10,20,30", &args, &param, err, sizeof err) != 0 ||
        cli_setup_base(&args, &base, err, sizeof err) != 0 || cli_setup_values(&args, &values, err, sizeof err) != 0) {
        fprintf(stderr, "fuzz_part: %s\n", err);
        abort();
    }
    const jc_SimOptions sim = jc_default_sim_options();
    cli_study_init(&def, JC_STUDY_GRID, &base, &values, &param, 1, &sim);
    jc_study_header(&def, header, sizeof header);
    job = cli_part_job_hash(&def, 0, 3);
    cli_part_job_line("sweep", job, 0, 3, job_line, sizeof job_line);
    return 0;
}

static int read_part(const uint8_t *data, size_t size, cli_PartRead *out, char *err, size_t err_len)
{
    static const uint8_t none[1] = {0};
    FILE *f = fmemopen((void *)(size ? data : none), size ? size : 1, "r");
    FUZZ_CHECK(f != NULL);
    if (size == 0) (void)fgetc(f); /* an empty file: at its end from the start */
    const cli_PartReader rd = {job_line, header, job, 1, 0, 3, NULL, NULL};
    err[0] = '\0';
    const int st = cli_part_read(f, &rd, out, err, err_len);
    fclose(f);
    return st;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    cli_PartRead got;
    char err[512];
    const int st = read_part(data, size, &got, err, sizeof err);
    FUZZ_CHECK(st == 0 || st == 1 || st == -1);
    if (st == -1) {
        FUZZ_CHECK(err[0] != '\0');
    } else if (st == 1) {
        FUZZ_CHECK(size < strlen(job_line) && memcmp(data, job_line, size) == 0);
    } else {
        FUZZ_CHECK(got.rows >= 0 && got.rows <= 3);
        FUZZ_CHECK(got.good_end >= (off_t)strlen(job_line) && (size_t)got.good_end <= size);
        FUZZ_CHECK(data[got.good_end - 1] == '\n');
        cli_PartRead again;
        FUZZ_CHECK(read_part(data, (size_t)got.good_end, &again, err, sizeof err) == 0);
        FUZZ_CHECK(again.rows == got.rows && again.good_end == got.good_end);
    }
    return 0;
}
