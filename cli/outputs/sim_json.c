/* `simulate --json`: the document built whole (cli_sim_json_doc, for runs
 * held in memory) and the same text written piece by piece as the events
 * arrive (cli_sim_json_begin/event/end), so that a run of millions of
 * events needs no more memory than one event. The pieces are printed by
 * cJSON itself (with exact numbers, cli_json_text) and re-indented to
 * their depth in the document, so the two texts are identical byte for
 * byte (tests/test_sim_json.c). */
#include "outputs.h"

#include <cjson/cJSON.h>
#include <stdlib.h>
#include <string.h>

/* termination ... summary: what follows the events. */
static void add_tail(cJSON *doc, const jc_Model *m, const jc_Run *run, const jc_RunSummary *sum)
{
    cJSON_AddStringToObject(doc, "termination", jc_termination_name(run->termination));
    cJSON_AddStringToObject(doc, "termination_detail", run->termination_detail);
    cJSON_AddNumberToObject(doc, "t_end", run->final_state.t_s);
    cJSON_AddItemToObject(doc, "energy", cli_json_energy(&run->energy));
    cJSON_AddStringToObject(doc, "impact_law", jc_impact_law_name(m->setup.impact_law));
    cJSON_AddNumberToObject(doc, "energy_gaining_impacts", run->energy_gaining_impacts);
    cJSON_AddNumberToObject(doc, "largest_impact_gain_J", run->largest_impact_gain_J);
    cJSON_AddNumberToObject(doc, "micro_slips", (double)run->micro_slips);
    cJSON_AddNumberToObject(doc, "rocking_period_s", run->rocking_period_s);
    cJSON *s = cJSON_AddObjectToObject(doc, "summary");
    cJSON_AddNumberToObject(s, "liftoffs", sum->liftoffs);
    cJSON_AddNumberToObject(s, "bounces", sum->bounces);
    cJSON_AddNumberToObject(s, "largest_hop", sum->largest_hop_m);
    if (sum->first_liftoff >= 0) {
        cJSON_AddNumberToObject(s, "first_liftoff_x", sum->first_liftoff_state.x_m);
        cJSON_AddNumberToObject(s, "first_liftoff_theta", sum->first_liftoff_state.theta_rad);
    } else {
        cJSON_AddNullToObject(s, "first_liftoff_x");
        cJSON_AddNullToObject(s, "first_liftoff_theta");
    }
}

cJSON *cli_sim_json_doc(const jc_Model *m, const jc_Run *run)
{
    cJSON *doc = cJSON_CreateObject();
    cJSON_AddItemToObject(doc, "setup", cli_json_setup(m));
    cJSON *ev = cJSON_AddArrayToObject(doc, "events");
    for (int i = 0; i < run->event_count; ++i) cJSON_AddItemToArray(ev, cli_json_event(&run->events[i]));
    jc_RunSummary sum;
    jc_run_summarize(run, &sum);
    add_tail(doc, m, run, &sum);
    return doc;
}

/* Writes text (cli_json_text's, formatted) from skip bytes on, dropping
 * drop bytes at its end, with tabs tabs after each line break: its depth in
 * the document. */
static int put_indented(FILE *out, char *text, size_t skip, size_t drop, int tabs)
{
    if (!text) return -1;
    const size_t n = strlen(text);
    int bad = skip + drop > n;
    for (size_t i = skip; !bad && i < n - drop; ++i) {
        bad = fputc(text[i], out) == EOF;
        for (int t = 0; !bad && text[i] == '\n' && t < tabs; ++t) bad = fputc('\t', out) == EOF;
    }
    free(text);
    return bad ? -1 : 0;
}

static int print_piece(FILE *out, cJSON *item, size_t skip, size_t drop, int tabs)
{
    char *text = cli_json_text(item, 1);
    cJSON_Delete(item);
    return put_indented(out, text, skip, drop, tabs);
}

int cli_sim_json_begin(FILE *out, const jc_Model *m)
{
    cJSON *head = cJSON_CreateObject();
    if (head) cJSON_AddItemToObject(head, "setup", cli_json_setup(m));
    /* "{ ... setup ...\n}" without its closing line, then the array opens. */
    if (print_piece(out, head, 0, 2, 0) != 0) return -1;
    return fputs(",\n\t\"events\":\t[", out) == EOF ? -1 : 0;
}

int cli_sim_json_event(FILE *out, const jc_Event *e, int index)
{
    if (index > 0 && fputs(", ", out) == EOF) return -1;
    return print_piece(out, cli_json_event(e), 0, 0, 2); /* an object inside the array: depth 2 */
}

int cli_sim_json_end(FILE *out, const jc_Model *m, const jc_Run *run, const jc_RunSummary *sum)
{
    if (fputs("],\n", out) == EOF) return -1;
    cJSON *tail = cJSON_CreateObject();
    if (tail) add_tail(tail, m, run, sum);
    /* "{\n" dropped: the members continue the document; puts' line break. */
    if (print_piece(out, tail, 2, 0, 0) != 0) return -1;
    return fputc('\n', out) == EOF ? -1 : 0;
}
