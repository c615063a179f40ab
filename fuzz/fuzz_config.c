/* Fuzz target: experiment files (cli/inputs/config.c), as bytes in memory.
 *
 * Invariants: a rejected file leaves a one-line message that starts with
 * the file's name; a file read is written back (cli_config_write) in a form
 * that reads back to the same setup, bit for bit, and writes again to the
 * same bytes. */
#define _POSIX_C_SOURCE 200809L
#include "fuzz.h"

#include "inputs.h"

#include <string.h>

#define MAX_INPUT 8192

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    return 0;
}

static int same_double(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

/* Field by field: the padding inside jc_Part is not part of the setup. */
static int same_setup(const jc_Setup *a, const jc_Setup *b)
{
    int same = same_double(a->body.radius_m, b->body.radius_m) && a->body.part_count == b->body.part_count;
    for (int i = 0; same && i < a->body.part_count; ++i) {
        const jc_Part *p = &a->body.parts[i], *q = &b->body.parts[i];
        same = p->kind == q->kind && same_double(p->mass_kg, q->mass_kg) && same_double(p->offset_m, q->offset_m) &&
               same_double(p->angle_rad, q->angle_rad) && same_double(p->radius_m, q->radius_m);
    }
    const double fa[] = {a->incline_rad, a->gravity_mps2, a->mu_static, a->mu_kinetic, a->restitution,
                         a->theta0_rad, a->omega0_radps, a->ramp_length_m, a->paper_cm_offset_m, a->length_m,
                         a->air_density_kgpm3, a->drag_coefficient, a->lift_coefficient, a->spin_drag_Nms2,
                         a->rolling_resistance_m};
    const double fb[] = {b->incline_rad, b->gravity_mps2, b->mu_static, b->mu_kinetic, b->restitution,
                         b->theta0_rad, b->omega0_radps, b->ramp_length_m, b->paper_cm_offset_m, b->length_m,
                         b->air_density_kgpm3, b->drag_coefficient, b->lift_coefficient, b->spin_drag_Nms2,
                         b->rolling_resistance_m};
    for (size_t i = 0; same && i < sizeof fa / sizeof fa[0]; ++i) same = same_double(fa[i], fb[i]);
    return same;
}

/* cli_config_write into memory; the caller frees. */
static char *dump(const jc_Setup *s, size_t *len)
{
    char *text = NULL;
    FILE *f = open_memstream(&text, len);
    if (!f) return NULL;
    FUZZ_CHECK(cli_config_write(f, s) == 0);
    fclose(f);
    return text;
}

static void check_round_trip(const jc_Setup *s)
{
    size_t len = 0, len2 = 0;
    char *text = dump(s, &len);
    if (!text) return;
    jc_Setup back = jc_paper_setup();
    char err[512];
    const int st = cli_config_parse("dump.ini", text, len, &back, err, sizeof err);
    if (st != 0) fprintf(stderr, "%s\n", err);
    FUZZ_CHECK(st == 0);
    FUZZ_CHECK(same_setup(s, &back));
    char *again = dump(&back, &len2);
    FUZZ_CHECK(again && len == len2 && memcmp(text, again, len) == 0);
    free(again);
    free(text);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > MAX_INPUT) return 0;
    jc_Setup s = jc_paper_setup();
    char err[512] = "";
    if (cli_config_parse("fuzz.ini", (const char *)data, size, &s, err, sizeof err) != 0) {
        FUZZ_CHECK(strncmp(err, "fuzz.ini", 8) == 0 && !strchr(err, '\n'));
        return 0;
    }
    check_round_trip(&s);
    /* What --config does next: the library's checks must take any setup. */
    jc_setup_validate(&s, err, sizeof err);
    return 0;
}
